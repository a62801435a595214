// Grid storage, indexing, binning, elevation and bounded hole filling.
#include "hylo/terrain/grid_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "hylo/common/check.h"
#include "hylo/terrain/grid_map_elevation.h"

namespace hylo::terrain {
namespace {

using hylo::PointCloud;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

GridGeometry MakeGeometry(int width, int height, double resolution_m) {
  GridGeometry g;
  g.resolution_m = resolution_m;
  g.width = width;
  g.height = height;
  return g;
}

TEST(GridGeometry, IndexingIsRowMajorWithRowZeroAtMinimumY) {
  GridGeometry g = MakeGeometry(4, 3, 0.5);
  g.corner_local = {-1.0, -0.5};
  EXPECT_EQ(g.Index(3, 2), 11u);
  EXPECT_EQ(g.Col(11), 3);
  EXPECT_EQ(g.Row(11), 2);
  const auto cell = g.CellOfLocal(-0.99, -0.49);
  ASSERT_TRUE(cell);
  EXPECT_EQ(*cell, Eigen::Vector2i(0, 0));
  EXPECT_EQ(*g.CellOfLocal(0.76, 0.9), Eigen::Vector2i(3, 2));
  EXPECT_FALSE(g.CellOfLocal(-1.01, 0.0));  // floor, not truncation, left of the corner
  EXPECT_FALSE(g.CellOfLocal(1.0, 0.0));    // the upper edge belongs to the next cell
  EXPECT_FALSE(g.CellOfLocal(std::nan(""), 0.0));
  EXPECT_TRUE(g.CentreLocal(0, 0).isApprox(Eigen::Vector2d(-0.75, -0.25)));
}

TEST(GridGeometry, WorldPositionsKeepUtmDigits) {
  GridGeometry g = MakeGeometry(10, 10, 0.1);
  g.origin_world = {523400.0, 4181200.0, 312.0};
  g.corner_local = {-0.3, 0.2};
  // 0.05 m must survive next to 4e6 m: only double (not float) arithmetic keeps it.
  EXPECT_NEAR(g.CentreWorld(0, 0).x(), 523399.75, 1e-9);
  EXPECT_NEAR(g.CentreWorld(0, 0).y(), 4181200.25, 1e-9);
  EXPECT_NEAR(g.CornerWorld().y(), 4181200.2, 1e-9);
}

TEST(FitGeometry, CoversEveryPointWithCornersOnResolutionMultiples) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-7.3f, 5.1f);
  PointCloud cloud(500);
  for (auto& p : cloud) p = {u(rng), u(rng), u(rng)};
  cloud.push_back({kNaN, 0.f, 0.f});
  const PointCloud other = {{9.99f, -8.f, 0.f}};
  const GridGeometry g = FitGeometry({&cloud, &other}, Eigen::Vector3d::Zero(), 0.25, 1000000);
  for (int i = 0; i < 2; ++i) {
    const double k = g.corner_local(i) / 0.25;
    EXPECT_NEAR(k, std::round(k), 1e-9);
  }
  for (std::size_t i = 0; i + 1 < cloud.size(); ++i) {
    EXPECT_TRUE(g.CellOfLocal(cloud[i].x(), cloud[i].y())) << i;
  }
  EXPECT_TRUE(g.CellOfLocal(9.99, -8.0));
  EXPECT_LE(g.width * 0.25, 9.99 + 7.3 + 0.5);  // no more than one spare cell per side
}

TEST(FitGeometry, EmptyOrAllNaNGivesAnEmptyGridAndHugeExtentThrows) {
  const PointCloud nan_cloud = {{kNaN, kNaN, kNaN}};
  EXPECT_EQ(FitGeometry({&nan_cloud}, Eigen::Vector3d::Zero(), 0.1, 100).NumCells(), 0u);
  const PointCloud far = {{0.f, 0.f, 0.f}, {5000.f, 5000.f, 0.f}};
  try {
    FitGeometry({&far}, Eigen::Vector3d::Zero(), 0.1, 1000000);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("coarser resolution"), std::string::npos) << e.what();
  }
}

TEST(BinPoints, MatchesBruteForceAndCountsSkippedPoints) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-3.f, 3.f);
  PointCloud cloud(3000);
  for (auto& p : cloud) p = {u(rng), u(rng), u(rng)};
  cloud[17] = {kNaN, 1.f, 1.f};
  GridGeometry g = MakeGeometry(20, 25, 0.2);
  g.corner_local = {-2.0, -2.5};  // some points fall outside
  const CellPoints bins = BinPoints(g, cloud);
  std::size_t outside = 0;
  std::vector<std::size_t> expected(g.NumCells(), 0);
  for (const auto& p : cloud) {
    const auto cell = g.CellOfLocal(p.x(), p.y());
    if (!cell)
      ++outside;
    else
      ++expected[g.Index(cell->x(), cell->y())];
  }
  EXPECT_EQ(bins.num_skipped, outside);
  for (std::size_t c = 0; c < g.NumCells(); ++c) {
    ASSERT_EQ(bins.Count(c), expected[c]) << c;
    for (std::size_t k = bins.offsets[c]; k < bins.offsets[c + 1]; ++k) {
      const auto& p = cloud[bins.point_indices[k]];
      EXPECT_EQ(g.Index(g.CellOfLocal(p.x(), p.y())->x(), g.CellOfLocal(p.x(), p.y())->y()), c);
    }
  }
}

TEST(GridMap, LayersAreNamedAndUnknownNamesAreProgrammerErrors) {
  GridMap grid(MakeGeometry(3, 2, 1.0));
  grid.AddLayer("a", 2.f)[grid.geometry().Index(2, 1)] = 5.f;
  EXPECT_EQ(grid.At("a", 2, 1), 5.f);
  EXPECT_EQ(grid.At("a", 0, 0), 2.f);
  EXPECT_TRUE(std::isnan(grid.At("a", 3, 0)));
  EXPECT_TRUE(grid.HasLayer("a"));
  EXPECT_THROW(grid.Layer("b"), InternalError);
}

/// Points on the plane z = 0.3 x - 0.2 y + 1, four per cell, except in `empty` cells.
PointCloud PlaneWithHoles(const GridGeometry& g, const std::vector<Eigen::Vector2i>& empty) {
  PointCloud cloud;
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      if (std::find(empty.begin(), empty.end(), Eigen::Vector2i(col, row)) != empty.end()) continue;
      for (const double dx : {-0.25, 0.25}) {
        for (const double dy : {-0.25, 0.25}) {
          const Eigen::Vector2d xy =
              g.CentreLocal(col, row) + g.resolution_m * Eigen::Vector2d(dx, dy);
          cloud.emplace_back(xy.x(), xy.y(), 0.3 * xy.x() - 0.2 * xy.y() + 1.0);
        }
      }
    }
  }
  return cloud;
}

std::vector<Eigen::Vector2i> Block(int col0, int row0, int cols, int rows) {
  std::vector<Eigen::Vector2i> cells;
  for (int r = row0; r < row0 + rows; ++r)
    for (int c = col0; c < col0 + cols; ++c) cells.emplace_back(c, r);
  return cells;
}

TEST(ComputeElevation, MeanHeightPerCell) {
  const GridGeometry g = MakeGeometry(10, 8, 0.5);
  const PointCloud cloud = PlaneWithHoles(g, {});
  GridMap grid(g);
  ElevationOptions options;
  options.max_hole_size_m = 0.0;
  const ElevationSummary s = ComputeElevation(cloud, BinPoints(g, cloud), options, &grid);
  EXPECT_EQ(s.measured_cells, g.NumCells());
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      const Eigen::Vector2d c = g.CentreLocal(col, row);
      // Four samples symmetric about the centre: the mean is the plane at the centre.
      EXPECT_NEAR(grid.At(layers::kElevation, col, row), 0.3 * c.x() - 0.2 * c.y() + 1.0, 1e-5);
      EXPECT_EQ(grid.At(layers::kPointCount, col, row), 4.f);
    }
  }
  options.min_points_per_cell = 5;
  EXPECT_EQ(ComputeElevation(cloud, BinPoints(g, cloud), options, &grid).measured_cells, 0u);
}

TEST(FillHoles, FillsOnlyEnclosedHolesUpToTheSetSize) {
  const GridGeometry g = MakeGeometry(30, 30, 0.2);
  std::vector<Eigen::Vector2i> empty = Block(5, 5, 3, 2);  // 0.6 x 0.4 m: fillable
  const auto big = Block(15, 12, 6, 6);                    // 1.2 x 1.2 m: too large
  const auto edge = Block(0, 20, 2, 2);                    // touches the border
  empty.insert(empty.end(), big.begin(), big.end());
  empty.insert(empty.end(), edge.begin(), edge.end());
  const PointCloud cloud = PlaneWithHoles(g, empty);
  GridMap grid(g);
  ElevationOptions options;
  options.max_hole_size_m = 0.6;
  const ElevationSummary s = ComputeElevation(cloud, BinPoints(g, cloud), options, &grid);
  EXPECT_EQ(s.holes_filled, 1u);
  EXPECT_EQ(s.filled_cells, 6u);
  EXPECT_EQ(s.holes_too_large, 1u);
  for (const auto& c : Block(5, 5, 3, 2)) {
    EXPECT_EQ(grid.At(layers::kFilled, c.x(), c.y()), 1.f);
    const Eigen::Vector2d xy = g.CentreLocal(c.x(), c.y());
    // Inverse-distance weighting of a plane: within the height change across one cell.
    EXPECT_NEAR(grid.At(layers::kElevation, c.x(), c.y()), 0.3 * xy.x() - 0.2 * xy.y() + 1.0,
                0.3 * 0.2);
  }
  for (const auto& c : big) EXPECT_TRUE(std::isnan(grid.At(layers::kElevation, c.x(), c.y())));
  for (const auto& c : edge) EXPECT_TRUE(std::isnan(grid.At(layers::kElevation, c.x(), c.y())));
  options.max_hole_size_m = 0.4;  // the 0.6 m wide hole is now too large
  EXPECT_EQ(ComputeElevation(cloud, BinPoints(g, cloud), options, &grid).filled_cells, 0u);
}

TEST(ElevationOptions, IsValidNamesTheField) {
  ElevationOptions options;
  std::string why;
  EXPECT_TRUE(options.IsValid(&why)) << why;
  options.max_hole_size_m = -1.0;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("max_hole_size_m"), std::string::npos) << why;
  options = ElevationOptions();
  options.min_points_per_cell = 0;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("min_points_per_cell = 0"), std::string::npos) << why;
}

}  // namespace
}  // namespace hylo::terrain
