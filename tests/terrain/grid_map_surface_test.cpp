// Surface layers near breaks in the terrain: the adaptive scale (a block of cells on the
// cell's own side instead of the centred footprint) and the cells left unknown at data edges.
#include "hylo/terrain/grid_map_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "hylo/terrain/traversability.h"

namespace hylo::terrain {
namespace {

using Points = std::vector<Eigen::Vector3d>;
constexpr double kRadToDeg = 180.0 / M_PI;
constexpr double kResolution = 0.25;

/// Uniform samples of z = height(x, y) over [-half, half]^2 with vertical Gaussian noise,
/// left out where `skip` says (an unseen gap).
Points Sample(const std::function<double(double, double)>& height, double half_m, int count,
              double noise_m, uint32_t seed, const std::function<bool(double, double)>& skip = {}) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-half_m, half_m);
  std::normal_distribution<double> noise(0.0, noise_m);
  Points points;
  for (int i = 0; i < count; ++i) {
    const double x = u(rng), y = u(rng);
    if (skip && skip(x, y)) continue;
    points.emplace_back(x, y, height(x, y) + noise(rng));
  }
  return points;
}

/// A cable trench along y, cut on cell boundaries: walls one cell wide (0.5 m over 0.25 m,
/// 63.4 deg) around a floor two cells wide, flat ground either side.
double Trench(double x, double) {
  const double w = kResolution;
  if (x < 0.0 || x >= 4 * w) return 0.0;
  if (x < w) return -0.5 * x / w;
  if (x < 3 * w) return -0.5;
  return -0.5 + 0.5 * (x - 3 * w) / w;
}

struct TrenchErrors {
  double floor_max_deg = 0.0;       ///< largest slope on the floor cells (truth 0)
  double beside_max_deg = 0.0;      ///< largest slope on the flat cells beside the walls
  double wall_max_error_deg = 0.0;  ///< largest |slope - 63.4| on the wall cells
  int floor = 0, beside = 0, walls = 0;
};

TrenchErrors MeasureTrench(const TraversabilityMap& map) {
  const GridGeometry& g = map.grid.geometry();
  const double wall_deg = std::atan(0.5 / kResolution) * kRadToDeg;
  TrenchErrors e;
  for (std::size_t c = 0; c < g.NumCells(); ++c) {
    const double slope = map.grid.Layer(layers::kSlope)[c];
    const Eigen::Vector2d xy = g.CentreWorld(g.Col(c), g.Row(c));
    if (std::isnan(slope) || std::abs(xy.y()) > 2.5) continue;  // sparse border rows
    const int column = static_cast<int>(std::floor(xy.x() / kResolution));
    if (column == 1 || column == 2) {
      e.floor_max_deg = std::max(e.floor_max_deg, slope);
      ++e.floor;
    } else if (column == 0 || column == 3) {
      e.wall_max_error_deg = std::max(e.wall_max_error_deg, std::abs(slope - wall_deg));
      ++e.walls;
    } else if (column == -1 || column == 4) {
      e.beside_max_deg = std::max(e.beside_max_deg, slope);
      ++e.beside;
    }
  }
  return e;
}

TraversabilityOptions TestOptions() {
  TraversabilityOptions options;
  options.resolution_m = kResolution;
  return options;
}

// The footprint (0.5 m) centred on a floor cell always straddles a wall; a block of cells
// on the floor alone does not. The cell-scale slope must follow the trench's profile.
TEST(SurfaceLayers, TrenchFloorWallsAndTheirSurroundingsKeepTheirOwnSlope) {
  const Points ground = Sample(Trench, 3.0, 150000, 0.005, 3);  // ~1000 points/m^2, 5 mm
  const TrenchErrors adaptive = MeasureTrench(ComputeTraversability(ground, {}, TestOptions()));
  TraversabilityOptions footprint_only = TestOptions();
  footprint_only.surface.scale_consistency_sigmas = 0.0;
  const TrenchErrors centred = MeasureTrench(ComputeTraversability(ground, {}, footprint_only));
  std::printf(
      "trench: max floor slope %.1f deg (footprint only %.1f), beside the walls %.1f "
      "(%.1f), max wall error %.1f (%.1f)\n",
      adaptive.floor_max_deg, centred.floor_max_deg, adaptive.beside_max_deg,
      centred.beside_max_deg, adaptive.wall_max_error_deg, centred.wall_max_error_deg);
  ASSERT_GT(adaptive.floor, 30);
  ASSERT_GT(adaptive.walls, 30);
  ASSERT_GT(adaptive.beside, 30);
  EXPECT_LT(adaptive.floor_max_deg, 5.0);
  EXPECT_LT(adaptive.beside_max_deg, 5.0);
  EXPECT_LT(adaptive.wall_max_error_deg, 5.0);
  // What the adaptive scale fixes: the centred footprint mixes walls into the flat cells.
  EXPECT_GT(centred.floor_max_deg, 20.0);
  EXPECT_GT(centred.wall_max_error_deg, 10.0);
}

// On a smooth surface the footprint's normal (the least noisy) is kept: the adaptive scale
// must not add the noise of the small blocks.
TEST(SurfaceLayers, SmoothSurfaceKeepsTheFootprintNormal) {
  const auto tilted = [](double x, double y) { return 0.2 * x - 0.1 * y; };
  const Points ground = Sample(tilted, 4.0, 40000, 0.02, 5);  // 625 points/m^2, 2 cm
  const TraversabilityMap map = ComputeTraversability(ground, {}, TestOptions());
  const SurfaceSummary& s = map.summary.surface;
  ASSERT_GT(s.cells_with_normal, 800u);
  EXPECT_LT(s.cells_finer_scale, s.cells_with_normal / 20) << s.cells_finer_scale;
  EXPECT_NEAR(s.noise_m, 0.02 / std::sqrt(1.0 + 0.05), 0.004);  // along the normal
}

// A square gap without points (a shadow, 1 m wide: too large to fill): the cells around it
// are unknown and counted, the rest of the plane free. A small gap (0.5 m, within
// max_hole_size_m) is filled and does not make its neighbours unknown. With the option off
// the cells around the large gap are estimated like any other.
TEST(SurfaceLayers, CellsAtADataEdgeAreUnknownAndCounted) {
  const auto flat = [](double, double) { return 0.0; };
  const auto in_gap = [](double x, double y) {
    return x >= 0.0 && x < 1.0 && y >= 0.0 && y < 1.0;  // 4 x 4 cells
  };
  const auto in_small_gap = [](double x, double y) {
    return x >= -2.0 && x < -1.5 && y >= -2.0 && y < -1.5;  // 2 x 2 cells
  };
  const Points ground = Sample(flat, 3.0, 60000, 0.01, 7, [&](double x, double y) {
    return in_gap(x, y) || in_small_gap(x, y);
  });
  const TraversabilityMap map = ComputeTraversability(ground, {}, TestOptions());
  const GridGeometry& g = map.grid.geometry();
  std::size_t ring = 0, ring_unknown = 0, far = 0, far_free = 0, small = 0, small_free = 0;
  for (std::size_t c = 0; c < g.NumCells(); ++c) {
    const Eigen::Vector2d xy = g.CentreWorld(g.Col(c), g.Row(c));
    const bool in_ring_x = xy.x() > -kResolution && xy.x() < 1.0 + kResolution;
    const bool in_ring_y = xy.y() > -kResolution && xy.y() < 1.0 + kResolution;
    const bool beside_gap =
        (in_ring_x && xy.y() > 0.0 && xy.y() < 1.0) || (in_ring_y && xy.x() > 0.0 && xy.x() < 1.0);
    if (beside_gap && !in_gap(xy.x(), xy.y())) {
      ++ring;
      ring_unknown += map.classes[c] == CellClass::kUnknown;
      EXPECT_TRUE(std::isnan(map.grid.Layer(layers::kSlope)[c]));
    } else if (std::abs(xy.x() + 1.75) < 0.5 && std::abs(xy.y() + 1.75) < 0.5) {
      ++small;  // the small gap and the cells around it
      small_free += map.classes[c] == CellClass::kFree;
    } else if (std::abs(xy.x() - 0.5) > 1.0 && std::abs(xy.y() - 0.5) > 1.0 &&
               std::abs(xy.x()) < 2.5 && std::abs(xy.y()) < 2.5) {
      ++far;
      far_free += map.classes[c] == CellClass::kFree;
    }
  }
  EXPECT_EQ(ring, 16u);  // four cells along each side
  EXPECT_EQ(ring_unknown, ring);
  EXPECT_EQ(far_free, far);
  EXPECT_EQ(small, 16u);
  EXPECT_EQ(small_free, small);
  EXPECT_EQ(map.summary.elevation.holes_filled, 1u);
  // The ring and the grid's own border ring: counted, not silently dropped.
  const std::size_t border = 2 * (g.width + g.height) - 4;
  EXPECT_EQ(map.summary.surface.cells_at_data_edge, ring + border);
  TraversabilityOptions estimate_edges = TestOptions();
  estimate_edges.surface.unknown_at_data_edge = false;
  const TraversabilityMap all = ComputeTraversability(ground, {}, estimate_edges);
  EXPECT_EQ(all.summary.surface.cells_at_data_edge, 0u);
  EXPECT_EQ(all.summary.surface.cells_with_normal,
            map.summary.surface.cells_with_normal + ring + border);
}

TEST(SurfaceOptions, IsValidNamesTheAdaptiveScaleField) {
  SurfaceOptions options;
  std::string why;
  EXPECT_TRUE(options.IsValid(&why)) << why;
  options.scale_consistency_sigmas = std::nan("");
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("scale_consistency_sigmas"), std::string::npos) << why;
}

}  // namespace
}  // namespace hylo::terrain
