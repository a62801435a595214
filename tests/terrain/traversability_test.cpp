// Surface layers, cost and obstacles on deterministic synthetic terrain: analytic surfaces
// (plane of known slope, paraboloid hill, step) sampled like a lidar would (density falling
// with range, noise along the ray), compared with their analytic slope.
#include "hylo/terrain/traversability.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "hylo/evaluation/traversability_eval.h"

namespace hylo::terrain {
namespace {

using evaluation::CellSelection;
using evaluation::CheckSteepCells;
using evaluation::CompareLayer;
using evaluation::CompareSlope;
using evaluation::LayerComparison;
using evaluation::SampleLayer;
using evaluation::SteepCellCheck;
using evaluation::TruthField;
using Points = std::vector<Eigen::Vector3d>;
constexpr double kDegToRad = M_PI / 180.0;

/// z = height(x, y) around (0, 0) with its analytic gradient, in a local frame.
struct Terrain {
  std::function<double(double, double)> height;
  std::function<Eigen::Vector2d(double, double)> gradient;
};

Terrain Plane(double slope_deg, double azimuth_rad) {
  const Eigen::Vector2d g = std::tan(slope_deg * kDegToRad) *
                            Eigen::Vector2d(std::cos(azimuth_rad), std::sin(azimuth_rad));
  return {[g](double x, double y) { return g.x() * x + g.y() * y; },
          [g](double, double) { return g; }};
}

/// A hill z = h - k (x^2 + y^2): slope atan(2 k r) grows from 0 at the top.
Terrain Paraboloid(double k) {
  return {[k](double x, double y) { return 3.0 - k * (x * x + y * y); },
          [k](double x, double y) { return Eigen::Vector2d(-2 * k * x, -2 * k * y); }};
}

/// Analytic slope in degrees at a world position, given the shift applied to the terrain.
TruthField TrueSlope(const Terrain& terrain, const Eigen::Vector3d& offset) {
  return [terrain, offset](double x, double y) {
    return std::atan(terrain.gradient(x - offset.x(), y - offset.y()).norm()) / kDegToRad;
  };
}

/// Lidar-like sampling of `terrain` over [-half, half]^2: a sensor 1.8 m above the ground at
/// the centre, point density falling as 1/r^2 beyond 4 m, Gaussian range noise along the ray.
/// Points are returned shifted by `offset` (e.g. UTM coordinates).
Points SampleLikeLidar(const Terrain& terrain, double half_extent_m, std::size_t candidates,
                       double range_noise_m, const Eigen::Vector3d& offset, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-half_extent_m, half_extent_m), unit(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, range_noise_m);
  const Eigen::Vector3d sensor(0.0, 0.0, terrain.height(0.0, 0.0) + 1.8);
  Points points;
  for (std::size_t i = 0; i < candidates; ++i) {
    const double x = u(rng), y = u(rng);
    const double r = std::hypot(x, y);
    if (r > 4.0 && unit(rng) > (4.0 / r) * (4.0 / r)) continue;
    const Eigen::Vector3d p(x, y, terrain.height(x, y));
    const Eigen::Vector3d ray = (p - sensor).normalized();
    points.push_back(p + noise(rng) * ray + offset);
  }
  return points;
}

TraversabilityOptions TestOptions() {
  TraversabilityOptions options;
  options.resolution_m = 0.25;
  return options;
}

class PlaneSlope : public ::testing::TestWithParam<double> {};

TEST_P(PlaneSlope, SlopeRmseWithinTwoDegrees) {
  const Terrain plane = Plane(GetParam(), 0.7);
  const Points ground = SampleLikeLidar(plane, 8.0, 250000, 0.02, Eigen::Vector3d::Zero(), 5);
  const TraversabilityMap map = ComputeTraversability(ground, {}, TestOptions());
  const LayerComparison slope = CompareSlope(map.grid, TrueSlope(plane, Eigen::Vector3d::Zero()));
  EXPECT_GT(slope.cells, 3000u);
  EXPECT_LE(slope.rmse, 2.0) << "slope " << GetParam() << " deg, bias " << slope.mean_error;
  std::printf("plane %.0f deg: slope RMSE %.3f deg over %zu cells (bias %.3f)\n", GetParam(),
              slope.rmse, slope.cells, slope.mean_error);
  const SteepCellCheck steep =
      CheckSteepCells(map.grid, map.classes, TrueSlope(plane, Eigen::Vector3d::Zero()), 20.0);
  if (GetParam() > 20.0) {
    EXPECT_GE(steep.fraction_marked, 0.95) << steep.marked_lethal << "/" << steep.steep_cells;
  } else {
    EXPECT_EQ(steep.steep_cells, 0u);
    EXPECT_EQ(map.summary.cells_per_class[static_cast<int>(CellClass::kLethal)], 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Slopes, PlaneSlope, ::testing::Values(0.0, 5.0, 15.0, 25.0, 35.0));

TEST(Traversability, ParaboloidHillSlopeAndSteepCells) {
  const Terrain hill = Paraboloid(0.06);  // 20 deg at r = 3.0 m, 44 deg at r = 8 m
  const Points ground = SampleLikeLidar(hill, 8.0, 300000, 0.02, Eigen::Vector3d::Zero(), 9);
  const TraversabilityMap map = ComputeTraversability(ground, {}, TestOptions());
  const TruthField truth = TrueSlope(hill, Eigen::Vector3d::Zero());
  const LayerComparison slope = CompareSlope(map.grid, truth);
  const SteepCellCheck steep = CheckSteepCells(map.grid, map.classes, truth, 20.0);
  std::printf(
      "paraboloid: slope RMSE %.3f deg over %zu cells; steep cells marked lethal "
      "%zu/%zu = %.4f\n",
      slope.rmse, slope.cells, steep.marked_lethal, steep.steep_cells, steep.fraction_marked);
  EXPECT_LE(slope.rmse, 2.0);
  EXPECT_GT(steep.steep_cells, 1000u);
  EXPECT_GE(steep.fraction_marked, 0.95);
  // And the gentle top is not lethal: cells under 15 deg true slope are traversable.
  const GridGeometry& g = map.grid.geometry();
  std::size_t gentle = 0, gentle_lethal = 0;
  for (std::size_t c = 0; c < g.NumCells(); ++c) {
    const Eigen::Vector2d xy = g.CentreWorld(g.Col(c), g.Row(c));
    if (map.classes[c] == CellClass::kUnknown || truth(xy.x(), xy.y()) > 15.0) continue;
    ++gentle;
    gentle_lethal += map.classes[c] == CellClass::kLethal;
  }
  EXPECT_GT(gentle, 200u);  // r < 2.2 m: ~250 cells
  EXPECT_EQ(gentle_lethal, 0u);
}

TEST(Traversability, StepIsLethalAlongItsEdgeOnly) {
  const Terrain step{[](double x, double) { return x >= 0.0 ? 0.5 : 0.0; },
                     [](double, double) { return Eigen::Vector2d::Zero(); }};
  const Points ground = SampleLikeLidar(step, 6.0, 150000, 0.01, Eigen::Vector3d::Zero(), 4);
  const TraversabilityMap map = ComputeTraversability(ground, {}, TestOptions());
  const GridGeometry& g = map.grid.geometry();
  std::size_t edge = 0, edge_lethal = 0, far = 0, far_free = 0;
  for (std::size_t c = 0; c < g.NumCells(); ++c) {
    if (map.grid.Layer(layers::kPointCount)[c] == 0.f) continue;
    const double x = g.CentreWorld(g.Col(c), g.Row(c)).x();
    // Ray noise scatters a few points past the sampled square: those sparse border cells
    // may have no neighbour across the step, so only the interior is checked.
    if (std::abs(g.CentreWorld(g.Col(c), g.Row(c)).y()) > 5.5) continue;
    if (std::abs(x) < g.resolution_m) {
      ++edge;
      edge_lethal += map.classes[c] == CellClass::kLethal;
      EXPECT_NEAR(map.grid.Layer(layers::kStep)[c], 0.5, 0.05)
          << "cell " << g.Col(c) << "," << g.Row(c) << " of " << g.width << "x" << g.height;
    } else if (std::abs(x) > 1.0 && map.classes[c] != CellClass::kUnknown) {  // not at an edge
      ++far;
      far_free += map.classes[c] == CellClass::kFree;
    }
  }
  EXPECT_GT(edge, 60u);
  EXPECT_EQ(edge_lethal, edge);
  EXPECT_GE(far_free, 0.99 * far);
}

// A bank one cell wide at 40 deg between two flats: its rise (0.21 m over 0.25 m, split over
// the cells it straddles) stays near the step limit and the footprint plane fit (0.5 m radius)
// mixes it with the flats; the cell-scale grade must mark the cells on it. The flats stay free.
TEST(Traversability, NarrowBankIsLethalThroughTheCellGrade) {
  const double width_m = 0.25;
  const double tan40 = std::tan(40.0 * kDegToRad);
  const Terrain bank{[=](double x, double) { return tan40 * std::clamp(x, 0.0, width_m); },
                     [=](double x, double) {
                       return Eigen::Vector2d(x >= 0.0 && x < width_m ? tan40 : 0.0, 0.0);
                     }};
  const Points ground = SampleLikeLidar(bank, 6.0, 200000, 0.01, Eigen::Vector3d::Zero(), 12);
  for (const bool use_grade : {true, false}) {
    TraversabilityOptions options = TestOptions();
    options.cost.lethal_on_cell_grade = use_grade;
    const TraversabilityMap map = ComputeTraversability(ground, {}, options);
    const GridGeometry& g = map.grid.geometry();
    std::size_t on_bank = 0, on_bank_lethal = 0, flat = 0, flat_free = 0;
    for (std::size_t c = 0; c < g.NumCells(); ++c) {
      if (map.classes[c] == CellClass::kUnknown) continue;
      const Eigen::Vector2d xy = g.CentreWorld(g.Col(c), g.Row(c));
      if (std::abs(xy.y()) > 5.5) continue;  // sparse border cells
      if (xy.x() > 0.0 && xy.x() < width_m) {
        ++on_bank;
        on_bank_lethal += map.classes[c] == CellClass::kLethal;
      } else if (xy.x() < -1.0 || xy.x() > 1.5) {
        ++flat;
        flat_free += map.classes[c] == CellClass::kFree;
      }
    }
    std::printf("bank, cell grade %s: %zu/%zu bank cells lethal, %zu/%zu flat cells free\n",
                use_grade ? "on" : "off", on_bank_lethal, on_bank, flat_free, flat);
    ASSERT_GT(on_bank, 30u);
    EXPECT_GE(flat_free, 0.99 * flat);
    if (use_grade) {
      EXPECT_GE(on_bank_lethal, 0.95 * on_bank);
    }
  }
}

TEST(Traversability, RoughnessMatchesVerticalNoise) {
  const Terrain flat = Plane(0.0, 0.0);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  std::normal_distribution<double> noise(0.0, 0.03);
  Points ground(100000);
  for (auto& p : ground) p = {u(rng), u(rng), noise(rng)};
  const TraversabilityMap map = ComputeTraversability(ground, {}, TestOptions());
  const LayerComparison roughness =
      CompareLayer(map.grid, layers::kRoughness, [](double, double) { return 0.03; });
  EXPECT_GE(roughness.cells, 900u);               // 32 x 32 cells less the border ring (data edge)
  EXPECT_NEAR(roughness.mean_error, 0.0, 0.005);  // sqrt of the smallest eigenvalue ~ sigma
}

// ---- obstacles ----

/// Flat ground over [-5, 5]^2 without returns under a 1 x 1 m box at (2, 1) (the box hides
/// the ground), the box surface as object points, plus a wire at 5 m and grass at 5 cm.
TEST(Traversability, BoxOfObjectPointsBecomesLethalWireAndGrassDoNot) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-5.0, 5.0), unit(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  const auto in_box = [](double x, double y) {
    return std::abs(x - 2.0) < 0.5 && std::abs(y - 1.0) < 0.5;
  };
  Points ground, objects;
  for (int i = 0; i < 120000; ++i) {
    const double x = u(rng), y = u(rng);
    if (!in_box(x, y)) ground.emplace_back(x, y, noise(rng));
  }
  for (int i = 0; i < 4000; ++i) {  // box faces and top, 1 m high
    const double a = unit(rng) - 0.5, h = unit(rng);
    const int face = i % 5;
    if (face == 4)
      objects.emplace_back(2.0 + a, 1.0 + (unit(rng) - 0.5), 1.0);
    else if (face < 2)
      objects.emplace_back(2.0 + (face ? 0.5 : -0.5), 1.0 + a, h);
    else
      objects.emplace_back(2.0 + a, 1.0 + (face == 3 ? 0.5 : -0.5), h);
  }
  for (int i = 0; i < 200; ++i) objects.emplace_back(-4.0 + 0.04 * i, -2.0, 5.0);   // wire
  for (int i = 0; i < 200; ++i) objects.emplace_back(-3.0, -4.0 + 0.04 * i, 0.05);  // grass
  const TraversabilityMap map = ComputeTraversability(ground, objects, TestOptions());
  const GridGeometry& g = map.grid.geometry();
  std::size_t box_cells = 0, box_lethal = 0, other_lethal = 0;
  for (std::size_t c = 0; c < g.NumCells(); ++c) {
    const Eigen::Vector2d xy = g.CentreWorld(g.Col(c), g.Row(c));
    if (in_box(xy.x(), xy.y())) {
      ++box_cells;
      box_lethal += map.classes[c] == CellClass::kLethal;
    } else if (std::abs(xy.x() - 2.0) > 0.75 || std::abs(xy.y() - 1.0) > 0.75) {
      other_lethal += map.classes[c] == CellClass::kLethal;
    }
  }
  EXPECT_EQ(box_cells, 16u);
  EXPECT_EQ(box_lethal, box_cells);  // the box interior has no ground yet is lethal
  EXPECT_EQ(other_lethal, 0u);       // wire (above the band) and grass (below) are not
  EXPECT_EQ(map.summary.obstacles.points_above_band, 200u);
  EXPECT_GE(map.summary.obstacles.points_below_band, 200u);  // + box-side points near the foot
}

// ---- bad input ----

TEST(Traversability, SingleHeightEverywhereIsFlatAndFree) {
  Points ground;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) ground.emplace_back(0.1 * i + 0.03, 0.1 * j + 0.07, 12.5);
  const TraversabilityMap map = ComputeTraversability(ground, {}, TestOptions());
  const auto& counts = map.summary.cells_per_class;
  const GridGeometry& g = map.grid.geometry();
  EXPECT_EQ(counts[static_cast<int>(CellClass::kLethal)], 0u);
  EXPECT_EQ(counts[static_cast<int>(CellClass::kCost)], 0u);
  // The border ring of the grid touches unseen land (a data edge): unknown; the rest free.
  const std::size_t interior = static_cast<std::size_t>(g.width - 2) * (g.height - 2);
  EXPECT_EQ(counts[static_cast<int>(CellClass::kFree)], interior);
  EXPECT_EQ(map.summary.surface.cells_at_data_edge, g.NumCells() - interior);
  EXPECT_LT(map.summary.slope.max_deg, 1e-4);  // acos rounding near 1 only
  for (const float r : map.grid.Layer(layers::kRoughness)) {
    if (!std::isnan(r)) {
      EXPECT_LT(r, 1e-4);  // NaN: the unknown border ring
    }
  }
}

TEST(Traversability, UtmCoordinatesGiveTheSameResultAsNearZero) {
  const Terrain plane = Plane(12.0, 2.1);
  const Eigen::Vector3d utm(523417.37, 4181263.81, 241.6);
  const Points near = SampleLikeLidar(plane, 6.0, 120000, 0.02, Eigen::Vector3d::Zero(), 8);
  const Points far = SampleLikeLidar(plane, 6.0, 120000, 0.02, utm, 8);
  const TraversabilityMap a = ComputeTraversability(near, {}, TestOptions());
  const TraversabilityMap b = ComputeTraversability(far, {}, TestOptions());
  const LayerComparison slope_b = CompareSlope(b.grid, TrueSlope(plane, utm));
  EXPECT_LE(slope_b.rmse, 2.0);
  EXPECT_NEAR(slope_b.rmse, CompareSlope(a.grid, TrueSlope(plane, Eigen::Vector3d::Zero())).rmse,
              0.1);
  // The origin is kept: the grid lies on the data in world coordinates, heights near zero.
  const Eigen::Vector2d corner = b.grid.geometry().CornerWorld();
  EXPECT_NEAR(corner.x(), utm.x() - 6.0, 0.3);
  EXPECT_NEAR(corner.y(), utm.y() - 6.0, 0.3);
  const auto& elevation = b.grid.Layer(layers::kElevation);
  const GridGeometry& g = b.grid.geometry();
  for (std::size_t c = 0; c < g.NumCells(); c += 97) {
    if (std::isnan(elevation[c])) continue;
    const Eigen::Vector2d xy = g.CentreWorld(g.Col(c), g.Row(c)) - utm.head<2>();
    EXPECT_NEAR(elevation[c] + g.origin_world.z(), utm.z() + plane.height(xy.x(), xy.y()), 0.08);
  }
}

TEST(Traversability, NaNPointsAreSkippedAndCounted) {
  const Terrain plane = Plane(10.0, 0.0);
  Points ground = SampleLikeLidar(plane, 4.0, 40000, 0.02, Eigen::Vector3d::Zero(), 1);
  const TraversabilityMap clean = ComputeTraversability(ground, {}, TestOptions());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ground.insert(ground.begin(), Eigen::Vector3d(nan, 0.0, 0.0));  // first: origin choice too
  ground.emplace_back(1.0, nan, 1.0);
  const Points objects = {{nan, nan, nan}};
  const TraversabilityMap dirty = ComputeTraversability(ground, objects, TestOptions());
  EXPECT_EQ(dirty.summary.ground_points_skipped, 2u);
  EXPECT_EQ(dirty.summary.object_points_skipped, 1u);
  EXPECT_EQ(dirty.summary.cells_per_class, clean.summary.cells_per_class);
  EXPECT_NEAR(dirty.summary.slope.mean_deg, clean.summary.slope.mean_deg, 1e-4);
}

TEST(Traversability, EmptyOrAllNaNGroundIsAClearError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Points& ground : {Points{}, Points{{nan, 1.0, 2.0}}}) {
    try {
      ComputeTraversability(ground, {}, TestOptions());
      FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("no finite point"), std::string::npos) << e.what();
    }
  }
}

TEST(Traversability, TooFewPointsForAPlaneAreUnknownNotFree) {
  TraversabilityOptions options = TestOptions();
  options.surface.unknown_at_data_edge = false;  // the plane fit itself must refuse
  const TraversabilityMap map = ComputeTraversability({{3.0, 4.0, 5.0}}, {}, options);
  ASSERT_EQ(map.grid.geometry().NumCells(), 1u);
  EXPECT_EQ(map.classes[0], CellClass::kUnknown);
  EXPECT_EQ(map.summary.surface.cells_too_few_points, 1u);
  // Points on one line (a single scan ring): the tilt across it is unobserved.
  Points line;
  for (int i = 0; i < 50; ++i) line.emplace_back(0.02 * i, 0.1, 0.0);
  const TraversabilityMap on_line = ComputeTraversability(line, {}, options);
  EXPECT_EQ(on_line.summary.surface.cells_with_normal, 0u);
  EXPECT_GT(on_line.summary.surface.cells_degenerate, 0u);
}

TEST(Traversability, SparseFootprintFallsBackToTheWiderNeighbourhood) {
  // Points 0.45 m apart on a 10 deg plane: a 0.5 m footprint holds fewer than min_points, the
  // 1 m fallback enough, so every cell with a point gets the plane's slope instead of unknown.
  const Terrain plane = Plane(10.0, 0.4);
  Points sparse;
  for (double x = -3.0; x <= 3.0; x += 0.45) {
    for (double y = -3.0; y <= 3.0; y += 0.45) sparse.emplace_back(x, y, plane.height(x, y));
  }
  TraversabilityOptions options = TestOptions();
  options.surface.unknown_at_data_edge = false;  // every point is alone in its cell
  const TraversabilityMap map = ComputeTraversability(sparse, {}, options);
  EXPECT_GT(map.summary.surface.cells_fallback, 100u);
  const LayerComparison slope = CompareSlope(map.grid, TrueSlope(plane, Eigen::Vector3d::Zero()));
  EXPECT_EQ(slope.cells, sparse.size());  // one point per cell, none left unknown
  EXPECT_LE(slope.rmse, 0.5);
  TraversabilityOptions no_fallback = options;
  no_fallback.surface.fallback_radius_m = no_fallback.surface.normal_radius_m;
  const TraversabilityMap strict = ComputeTraversability(sparse, {}, no_fallback);
  EXPECT_EQ(strict.summary.surface.cells_fallback, 0u);
  EXPECT_GT(strict.summary.surface.cells_too_few_points, 100u);
}

TEST(Traversability, InvalidOptionsNameTheField) {
  TraversabilityOptions options = TestOptions();
  options.cost.max_slope_deg = 95.0;
  try {
    ComputeTraversability({{0, 0, 0}}, {}, options);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cost.max_slope_deg = 95"), std::string::npos) << e.what();
  }
  std::string why;
  options = TestOptions();
  options.resolution_m = 0.0;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("resolution_m = 0"), std::string::npos) << why;
  options = TestOptions();
  options.surface.min_points = 2;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("surface.min_points = 2"), std::string::npos) << why;
  options = TestOptions();
  options.surface.fallback_radius_m = 0.2;  // below normal_radius_m
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("surface.fallback_radius_m = 0.2"), std::string::npos) << why;
  options = TestOptions();
  options.surface.scale_consistency_sigmas = -1.0;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("surface.scale_consistency_sigmas = -1"), std::string::npos) << why;
  options = TestOptions();
  options.cost.obstacle_max_height_m = 0.1;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("obstacle_max_height_m"), std::string::npos) << why;
}

// ---- evaluation helpers ----

TEST(Evaluation, SampleLayerAndCompareAgainstAnotherGrid) {
  GridGeometry g;
  g.origin_world = {1000.0, 2000.0, 0.0};
  g.resolution_m = 0.5;
  g.width = 4;
  g.height = 3;
  GridMap truth(g);
  auto& values = truth.AddLayer("slope", 0.f);
  for (std::size_t c = 0; c < values.size(); ++c) values[c] = static_cast<float>(c);
  const TruthField field = SampleLayer(truth, "slope");
  EXPECT_EQ(field(1000.6, 2001.2), 9.0);  // col 1, row 2
  EXPECT_TRUE(std::isnan(field(999.9, 2000.0)));
  GridMap estimate(g);
  estimate.AddLayer(layers::kPointCount, 1.f);
  auto& slope = estimate.AddLayer(layers::kSlope, 0.f);
  for (std::size_t c = 0; c < slope.size(); ++c) slope[c] = static_cast<float>(c) + 1.f;
  slope[0] = std::numeric_limits<float>::quiet_NaN();
  const LayerComparison cmp = CompareSlope(estimate, field);
  EXPECT_EQ(cmp.cells, 11u);
  EXPECT_DOUBLE_EQ(cmp.rmse, 1.0);
  EXPECT_DOUBLE_EQ(cmp.mean_error, 1.0);
  std::vector<CellClass> classes(g.NumCells(), CellClass::kFree);
  classes[11] = CellClass::kLethal;
  const SteepCellCheck steep = CheckSteepCells(estimate, classes, field, 9.5);  // cells 10, 11
  EXPECT_EQ(steep.steep_cells, 2u);
  EXPECT_EQ(steep.marked_lethal, 1u);
  EXPECT_DOUBLE_EQ(steep.fraction_marked, 0.5);
  EXPECT_EQ(steep.steep_unknown, 0u);
  // A steep cell with points but no slope is counted apart, not as a missed steep cell.
  slope[10] = std::numeric_limits<float>::quiet_NaN();
  classes[10] = CellClass::kUnknown;
  const SteepCellCheck with_unknown = CheckSteepCells(estimate, classes, field, 9.5);
  EXPECT_EQ(with_unknown.steep_cells, 1u);
  EXPECT_EQ(with_unknown.steep_unknown, 1u);
  EXPECT_DOUBLE_EQ(with_unknown.fraction_marked, 1.0);
}

}  // namespace
}  // namespace hylo::terrain
