// Cloth simulation filter: synthetic terrains with known labels, bad input, the hole fills.
// The real-data evaluations (ISPRS, csf_sample) are in cloth_filter_data_test.cpp.
#include "hylo/terrain/cloth_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "hylo/terrain/cloth_filter_surface.h"

namespace hylo::terrain {
namespace {

struct LabelledCloud {
  PointCloud points;
  std::vector<bool> is_ground;
};

struct Box {
  float x0, y0, x1, y1, height_m;  ///< footprint (m) and height above the terrain (m)
  bool Contains(float x, float y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

// Airborne-like sampling: `density` points per m^2 on `terrain`, replaced by roof points
// inside box footprints (a roof hides the ground below it), plus a few wall points.
LabelledCloud MakeScene(float size_m, float density,
                        const std::function<float(float, float)>& terrain,
                        const std::vector<Box>& boxes, float noise_m, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uniform(0.f, size_m);
  std::normal_distribution<float> noise(0.f, noise_m);
  LabelledCloud cloud;
  const int count = static_cast<int>(size_m * size_m * density);
  for (int i = 0; i < count; ++i) {
    const float x = uniform(rng), y = uniform(rng);
    float z = terrain(x, y) + noise(rng);
    bool ground = true;
    for (const Box& box : boxes) {
      if (!box.Contains(x, y)) continue;
      z += box.height_m;
      ground = false;
    }
    cloud.points.emplace_back(x, y, z);
    cloud.is_ground.push_back(ground);
  }
  for (const Box& box : boxes) {  // one wall, sparse: walls are rare in airborne data
    for (float h = 1.f; h < box.height_m; h += 1.f) {
      cloud.points.emplace_back(box.x0, 0.5f * (box.y0 + box.y1), terrain(box.x0, box.y0) + h);
      cloud.is_ground.push_back(false);
    }
  }
  return cloud;
}

struct Agreement {
  double ground_kept = 0;      ///< fraction of true ground labelled ground
  double objects_removed = 0;  ///< fraction of true objects labelled objects
};

Agreement Compare(const LabelledCloud& cloud, const ClothFilterResult& result) {
  std::size_t ground = 0, ground_ok = 0, objects = 0, objects_ok = 0;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if (cloud.is_ground[i]) {
      ++ground;
      ground_ok += result.labels[i] == GroundLabel::kGround;
    } else {
      ++objects;
      objects_ok += result.labels[i] == GroundLabel::kObject;
    }
  }
  return {ground ? double(ground_ok) / ground : 1.0, objects ? double(objects_ok) / objects : 1.0};
}

TEST(ClothFilterOptions, DefaultsAreThePapersAndValid) {
  const ClothFilterOptions options;
  std::string why;
  EXPECT_TRUE(options.IsValid(&why)) << why;
  EXPECT_EQ(options.rigidness, 3);
  EXPECT_DOUBLE_EQ(options.time_step, 0.65);
  EXPECT_DOUBLE_EQ(options.class_threshold_m, 0.5);
  EXPECT_EQ(options.max_iterations, 500);
}

TEST(ClothFilterOptions, InvalidFieldIsNamed) {
  ClothFilterOptions options;
  options.cloth_resolution_m = -1.0;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("cloth_resolution_m"), std::string::npos) << why;
  options = ClothFilterOptions{};
  options.rigidness = 0;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("rigidness"), std::string::npos) << why;
  options.time_step = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(FilterGroundLocal({{0, 0, 0}}, options), std::invalid_argument);
}

TEST(ClothFilter, FlatNoisyTerrainIsAllGround) {
  const LabelledCloud cloud = MakeScene(
      60.f, 2.f, [](float, float) { return 0.f; }, {}, 0.05f, 1);
  const ClothFilterResult result = FilterGroundLocal(cloud.points, ClothFilterOptions{});
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_GE(Compare(cloud, result).ground_kept, 0.999) << result.message;
  EXPECT_TRUE(result.converged);
}

TEST(ClothFilter, GentleSlopeIsAllGround) {
  // 10 degrees: the cloth must follow it (with slope post-processing, the paper's default).
  const float tan10 = std::tan(10.f * 3.14159265f / 180.f);
  const LabelledCloud cloud = MakeScene(
      60.f, 2.f, [tan10](float x, float) { return tan10 * x; }, {}, 0.03f, 2);
  const ClothFilterResult result = FilterGroundLocal(cloud.points, ClothFilterOptions{});
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_GE(Compare(cloud, result).ground_kept, 0.99) << result.message;
}

TEST(ClothFilter, BuildingsOnASteppedTerrainAreObjects) {
  // A 1 m terrace step with three buildings (one across the step); the cloth is stiff enough
  // to span the 10-20 m roofs but follows the step.
  const auto terrain = [](float x, float y) { return (x > 40.f ? 1.f : 0.f) + 0.02f * y; };
  const std::vector<Box> boxes = {
      {10, 10, 25, 25, 8.f}, {50, 50, 62, 70, 5.f}, {35, 60, 45, 72, 3.f}};
  const LabelledCloud cloud = MakeScene(80.f, 2.f, terrain, boxes, 0.03f, 3);
  const ClothFilterResult result = FilterGroundLocal(cloud.points, ClothFilterOptions{});
  ASSERT_TRUE(result.ok) << result.message;
  const Agreement agreement = Compare(cloud, result);
  EXPECT_GE(agreement.ground_kept, 0.98) << result.message;
  EXPECT_GE(agreement.objects_removed, 0.99) << result.message;
}

// Points 0.55 m above the terrain (vertically) are 0.55 m from a flat cloth but only
// 0.55 cos(35 deg) = 0.45 m from a cloth on a 35 deg slope: within hcc 0.5 measured to the
// cloth surface, beyond it measured vertically. The terrain is a lattice on the cloth's
// particles (GR 0.3 m, a rise of 0.21 m per particle that the slope post-processing follows),
// so the settled cloth is the plane itself and only the distance rule decides.
TEST(ClothFilter, DistanceToTheClothIsMeasuredToItsSurface) {
  constexpr float kGr = 0.3f;
  for (const float slope_deg : {0.f, 35.f}) {
    const float tan_slope = std::tan(slope_deg * 3.14159265f / 180.f);
    PointCloud points;
    for (int i = 0; i <= 60; ++i) {
      for (int j = 0; j <= 60; ++j) points.emplace_back(kGr * i, kGr * j, tan_slope * kGr * i);
    }
    const std::size_t num_terrain = points.size();
    for (float x = 1.05f; x < 17.f; x += 1.5f) {
      for (float y = 1.05f; y < 17.f; y += 1.5f) points.emplace_back(x, y, tan_slope * x + 0.55f);
    }
    for (const bool along_normal : {true, false}) {
      ClothFilterOptions options;
      options.cloth_resolution_m = kGr;
      options.class_distance_along_normal = along_normal;
      const ClothFilterResult result = FilterGroundLocal(points, options);
      ASSERT_TRUE(result.ok) << result.message;
      std::size_t terrain_ground = 0, raised_ground = 0;
      for (std::size_t i = 0; i < points.size(); ++i) {
        const bool ground = result.labels[i] == GroundLabel::kGround;
        (i < num_terrain ? terrain_ground : raised_ground) += ground;
      }
      const std::size_t num_raised = points.size() - num_terrain;
      EXPECT_EQ(terrain_ground, num_terrain) << slope_deg << " deg";
      const bool expect_ground = along_normal && slope_deg > 30.f;
      EXPECT_EQ(raised_ground, expect_ground ? num_raised : 0u)
          << slope_deg << " deg, along normal " << along_normal;
    }
  }
}

// A bridge: a road embankment ramps up 6 m over 30 m (0.2 m per particle, a slope the
// post-processing follows) onto a 40 m deck that hides the valley floor under it. The deck
// joins the ramps without a step, so the height test alone walks onto it; the cloth spans the
// deck 6 m above its surface, so the gap test stops there (ISPRS samp21).
TEST(ClothFilter, SlopePostProcessingDoesNotPinABridgeDeck) {
  const auto ramp = [](float x) {
    if (x < 20.f || x > 120.f) return 0.f;
    if (x < 50.f) return 0.2f * (x - 20.f);
    if (x > 90.f) return 0.2f * (120.f - x);
    return 6.f;
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.f, 140.f);
  std::normal_distribution<float> noise(0.f, 0.03f);
  LabelledCloud cloud;
  for (int i = 0; i < 140 * 140 * 2; ++i) {
    const float x = uniform(rng), y = uniform(rng);
    const bool on_road = y > 60.f && y < 75.f;
    const bool deck = on_road && x >= 50.f && x <= 90.f;
    cloud.points.emplace_back(x, y, (on_road ? ramp(x) : 0.f) + noise(rng));
    cloud.is_ground.push_back(!deck);
  }
  ClothFilterOptions options;
  const Agreement with_gap = Compare(cloud, FilterGroundLocal(cloud.points, options));
  EXPECT_GE(with_gap.objects_removed, 0.95);
  EXPECT_GE(with_gap.ground_kept, 0.96);
  // Without the gap test (the reference release) the deck is called ground: the test above can
  // fail, and it fails for the reason it names.
  options.slope_max_cloth_gap_m = std::numeric_limits<double>::infinity();
  const Agreement without_gap = Compare(cloud, FilterGroundLocal(cloud.points, options));
  EXPECT_LT(without_gap.objects_removed, 0.5);
}

// Multipath returns 30 m under the terrain, in a cluster of 30 points that support each other
// (as under a building in ISPRS samp41): by count they pass any small support test, so only the
// fraction keeps the cloth from hanging on them like a tent over the terrain around.
TEST(ClothFilter, ClusterOfLowOutliersDoesNotHoldTheClothUp) {
  LabelledCloud cloud = MakeScene(
      100.f, 1.f, [](float x, float) { return 0.01f * x; }, {}, 0.05f, 8);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> spot(45.f, 60.f);
  for (int i = 0; i < 30; ++i) {
    const float x = spot(rng), y = spot(rng);
    cloud.points.emplace_back(x, y, 0.01f * x - 30.f);
    cloud.is_ground.push_back(false);
  }
  ClothFilterOptions options;
  const ClothFilterResult result = FilterGroundLocal(cloud.points, options);
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_GE(result.num_low_outliers, 30u);
  EXPECT_GE(Compare(cloud, result).ground_kept, 0.99) << result.message;
  options.low_outlier_max_fraction = 0.0;  // the count alone
  const ClothFilterResult by_count = FilterGroundLocal(cloud.points, options);
  EXPECT_LT(Compare(cloud, by_count).ground_kept, 0.95) << by_count.message;
}

// Airborne density at ISPRS sites 5 and 6 (0.2 points/m^2): a count of neighbours in small cells
// took valid terrain points for outliers there (500-900 per sample); the fraction does not.
TEST(ClothFilter, SparseCleanTerrainHasNoLowOutliers) {
  for (const float density : {0.2f, 4.f}) {
    const LabelledCloud cloud = MakeScene(
        120.f, density, [](float x, float y) { return 0.05f * x + 2.f * std::sin(0.05f * y); }, {},
        0.05f, 10);
    const ClothFilterResult result = FilterGroundLocal(cloud.points, ClothFilterOptions{});
    ASSERT_TRUE(result.ok) << result.message;
    EXPECT_EQ(result.num_low_outliers, 0u) << density << " points/m^2";
    EXPECT_GE(Compare(cloud, result).ground_kept, 0.99) << density << " points/m^2";
  }
}

TEST(ClothFilter, EmptyAndAllNanCloudsAreReportedNotClassified) {
  const ClothFilterResult empty = FilterGroundLocal({}, ClothFilterOptions{});
  EXPECT_FALSE(empty.ok);
  EXPECT_EQ(empty.message, "empty cloud");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const ClothFilterResult nans =
      FilterGroundLocal({{nan, 0, 0}, {0, nan, 1}}, ClothFilterOptions{});
  EXPECT_FALSE(nans.ok);
  EXPECT_EQ(nans.num_invalid, 2u);
  ASSERT_EQ(nans.labels.size(), 2u);
  EXPECT_EQ(nans.labels[0], GroundLabel::kInvalid);
}

TEST(ClothFilter, NanPointsAreSkippedAndTheRestClassified) {
  LabelledCloud cloud = MakeScene(
      40.f, 2.f, [](float, float) { return 0.f; }, {{10, 10, 20, 20, 6.f}}, 0.02f, 4);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.points.insert(cloud.points.begin() + 5, Eigen::Vector3f(nan, 1.f, 1.f));
  cloud.is_ground.insert(cloud.is_ground.begin() + 5, false);
  const ClothFilterResult result = FilterGroundLocal(cloud.points, ClothFilterOptions{});
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_EQ(result.num_invalid, 1u);
  EXPECT_EQ(result.labels[5], GroundLabel::kInvalid);
  EXPECT_EQ(result.num_ground + result.num_objects + 1, cloud.points.size());
  const Agreement agreement = Compare(cloud, result);
  EXPECT_GE(agreement.ground_kept, 0.99);
  EXPECT_GE(agreement.objects_removed, 0.99);  // the NaN point counts as a non-object here
}

TEST(ClothFilter, SingleHeightEverywhereIsAllGround) {
  PointCloud points;
  for (int i = 0; i < 30; ++i) {
    for (int j = 0; j < 30; ++j) points.emplace_back(0.7f * i, 0.7f * j, 12.5f);
  }
  const ClothFilterResult result = FilterGroundLocal(points, ClothFilterOptions{});
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_EQ(result.num_ground, points.size());
  // Degenerate: one point, and a vertical line of points (zero horizontal extent).
  EXPECT_EQ(FilterGroundLocal({{1, 2, 3}}, ClothFilterOptions{}).num_ground, 1u);
  const ClothFilterResult pole =
      FilterGroundLocal({{1, 2, 0}, {1, 2, 5}, {1, 2, 10}}, ClothFilterOptions{});
  ASSERT_TRUE(pole.ok);
  EXPECT_EQ(pole.labels[0], GroundLabel::kGround);
  EXPECT_EQ(pole.labels[2], GroundLabel::kObject);
}

TEST(ClothFilter, UtmCoordinatesGiveTheSameLabelsAsNearZero) {
  const LabelledCloud cloud = MakeScene(
      50.f, 2.f, [](float x, float) { return 0.05f * x; }, {{15, 15, 30, 28, 7.f}}, 0.03f, 5);
  const Eigen::Vector3d utm(512345.678, 5612345.432, 412.3);
  std::vector<Eigen::Vector3d> world;
  for (const Eigen::Vector3f& p : cloud.points) world.push_back(p.cast<double>() + utm);
  const ClothFilterResult near_zero = FilterGroundLocal(cloud.points, ClothFilterOptions{});
  const ClothFilterResult in_utm = FilterGround(world, ClothFilterOptions{});
  ASSERT_TRUE(in_utm.ok) << in_utm.message;
  EXPECT_LT((in_utm.origin_world - utm).norm(), 100.0);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < world.size(); ++i) differ += near_zero.labels[i] != in_utm.labels[i];
  // The shifted cloud samples the cloth grid at other phases, so a handful of points right at
  // the threshold may flip; nothing more.
  EXPECT_LE(differ, world.size() / 200) << differ << " of " << world.size();
  EXPECT_GE(Compare(cloud, in_utm).objects_removed, 0.99);
}

// The nearest fill against brute force: a sparse random grid (3 % of particles known, each
// with its own value) where every hole must take the value of a known particle at the least
// Euclidean distance; the propagation may miss by a cell in rare Voronoi corners, no more.
TEST(ClothHoleFill, NearestTakesTheNearestKnownParticle) {
  cloth::ClothGrid grid;
  grid.cols = 70;
  grid.rows = 50;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> height(grid.Size(), std::numeric_limits<double>::quiet_NaN());
  std::vector<std::size_t> known;
  for (std::size_t i = 0; i < grid.Size(); ++i) {
    if (unit(rng) >= 0.03) continue;
    height[i] = static_cast<double>(known.size());  // the value names its particle
    known.push_back(i);
  }
  ASSERT_GT(known.size(), 50u);
  const std::vector<double> measured = height;
  EXPECT_EQ(cloth::FillHolesFromNearest(grid, &height), grid.Size() - known.size());
  auto distance = [&](std::size_t a, std::size_t b) {
    return std::hypot(double(int(a % grid.cols) - int(b % grid.cols)),
                      double(int(a / grid.cols) - int(b / grid.cols)));
  };
  std::size_t exact = 0, holes = 0;
  for (std::size_t i = 0; i < grid.Size(); ++i) {
    if (!std::isnan(measured[i])) {
      EXPECT_EQ(height[i], measured[i]);  // known particles keep their height
      continue;
    }
    ++holes;
    double nearest = std::numeric_limits<double>::infinity();
    for (const std::size_t k : known) nearest = std::min(nearest, distance(i, k));
    const double taken = distance(i, known[static_cast<std::size_t>(height[i])]);
    EXPECT_LE(taken, nearest + 1.0) << "particle " << i;
    exact += taken <= nearest + 1e-9;
  }
  EXPECT_GE(double(exact) / holes, 0.99);
}

}  // namespace
}  // namespace hylo::terrain
