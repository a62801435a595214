// SMRF on synthetic terrain with known ground: banks up to 35 deg, buildings, a bridge deck
// over a cutting, low outliers; its options; the clear answers to bad input beyond those of
// ground_filter_test.cpp. The real samples are scored in ground_filter_data_test.cpp.
#include "hylo/terrain/ground_smrf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "ground_test_scenes.h"
#include "hylo/terrain/ground_filter.h"

namespace hylo::terrain {
namespace {

using scenes::Bank;
using scenes::MakeScene;
using scenes::Scene;
using scenes::SceneScore;
using scenes::SceneSpec;

TEST(SmrfOptions, DefaultsAreValidAndInvalidFieldsAreNamed) {
  std::string why;
  EXPECT_TRUE(SmrfOptions{}.IsValid(&why)) << why;
  const auto expect_named = [](SmrfOptions options, const char* field) {
    std::string reason;
    EXPECT_FALSE(options.IsValid(&reason)) << field;
    EXPECT_NE(reason.find(field), std::string::npos) << reason;
  };
  SmrfOptions o;
  o.cell_m = 0;
  expect_named(o, "cell_m");
  o = {};
  o.slope = std::nan("");
  expect_named(o, "slope");
  o = {};
  o.max_window_m = 0.5;  // smaller than a cell
  expect_named(o, "max_window_m");
  o = {};
  o.elevation_threshold_m = -0.1;
  expect_named(o, "elevation_threshold_m");
  o = {};
  o.elevation_scaler = -1;
  expect_named(o, "elevation_scaler");
  o = {};
  o.low_outlier_window_m = -1;
  expect_named(o, "low_outlier_window_m");
  o.low_outlier_window_m = 1;
  o.max_cells = 0;
  expect_named(o, "max_cells");
  EXPECT_THROW(FilterGroundSmrfLocal({{0, 0, 0}}, o), std::invalid_argument);
}

// A substation-like cut: a bank of `angle` up to a plateau 6 m higher, and beyond it a bank
// down again at the same angle, on gently sloping ground.
SceneSpec BanksAt(float angle_deg) {
  SceneSpec spec;
  spec.size_m = 120.f;
  spec.density = 2.f;
  spec.terrain = [angle_deg](float x, float y) {
    return 0.02f * y + Bank(x, 30.f, 6.f, angle_deg) - Bank(x, 80.f, 6.f, angle_deg);
  };
  return spec;
}

TEST(Smrf, BanksUpTo35DegreesStayGround) {
  for (const float angle : {15.f, 25.f, 35.f}) {
    const Scene scene = MakeScene(BanksAt(angle));
    const SmrfResult result = FilterGroundSmrfLocal(scene.points, SmrfOptions{});
    ASSERT_TRUE(result.ok) << result.message;
    EXPECT_GE(scenes::Score(scene, result.labels).ground_kept, 0.99)
        << angle << " deg: " << result.message;
  }
}

TEST(Smrf, BuildingsOnABankedSiteAreObjects) {
  SceneSpec spec = BanksAt(35.f);
  spec.slabs = {{5, 10, 20, 30, 7},      // on the low ground
                {45, 40, 65, 55, 10},    // on the plateau
                {95, 90, 112, 110, 4}};  // a low shed
  const Scene scene = MakeScene(spec);
  const SmrfResult result = FilterGroundSmrfLocal(scene.points, SmrfOptions{});
  ASSERT_TRUE(result.ok) << result.message;
  const SceneScore score = scenes::Score(scene, result.labels);
  EXPECT_GE(score.ground_kept, 0.98) << result.message;
  EXPECT_GE(score.objects_removed, 0.98) << result.message;
}

// A road in a 5 m cutting runs along y; a 6 m wide deck crosses it at the original level.
TEST(Smrf, BridgeDeckOverACuttingIsAnObject) {
  SceneSpec spec;
  spec.size_m = 100.f;
  spec.terrain = [](float x, float) {
    return -Bank(x, 35.f, 5.f, 35.f) + Bank(x, 58.f, 5.f, 35.f);  // floor from ~42 to ~58 m
  };
  spec.slabs = {{37, 47, 63, 53, 0.3f, true}};
  const Scene scene = MakeScene(spec);
  const SmrfResult result = FilterGroundSmrfLocal(scene.points, SmrfOptions{});
  ASSERT_TRUE(result.ok) << result.message;
  const SceneScore score = scenes::Score(scene, result.labels);
  EXPECT_GE(score.ground_kept, 0.98) << result.message;
  EXPECT_GE(score.objects_removed, 0.90) << result.message;
}

// A road embankment 3 m high with 35 deg sides and a 6 m top: the opening takes its top out
// as it takes out a building (both are raised and narrower than the window); the DEM must
// bring it back from the slopes of its sides, and the house beside it must stay an object.
TEST(Smrf, AnEmbankmentNarrowerThanTheWindowStaysGround) {
  for (const float density : {0.5f, 2.f}) {
    SceneSpec spec;
    spec.size_m = 100.f;
    spec.density = density;
    spec.terrain = [](float x, float y) {
      return 0.01f * y + Bank(x, 40.f, 3.f, 35.f) - Bank(x, 50.3f, 3.f, 35.f);
    };
    spec.slabs = {{70, 30, 82, 45, 3}};
    const Scene scene = MakeScene(spec);
    const SmrfResult result = FilterGroundSmrfLocal(scene.points, GroundFilterOptions().smrf);
    ASSERT_TRUE(result.ok) << result.message;
    const SceneScore score = scenes::Score(scene, result.labels);
    EXPECT_GE(score.ground_kept, 0.99) << density << " points/m^2: " << result.message;
    EXPECT_GE(score.objects_removed, 0.95) << density << " points/m^2: " << result.message;
  }
}

TEST(Smrf, LowOutliersAreObjectsAndDoNotPullTheGroundDown) {
  SceneSpec spec;
  spec.size_m = 80.f;
  spec.terrain = [](float x, float y) { return 0.1f * x + 0.5f * std::sin(0.1f * y); };
  spec.low_outliers = 30;
  spec.low_outlier_depth_m = 12.f;
  const Scene scene = MakeScene(spec);
  const SmrfResult result = FilterGroundSmrfLocal(scene.points, SmrfOptions{});
  ASSERT_TRUE(result.ok) << result.message;
  const SceneScore score = scenes::Score(scene, result.labels);
  EXPECT_EQ(score.outliers_removed, 1.0) << result.message;
  EXPECT_GE(score.ground_kept, 0.995) << result.message;
  EXPECT_GE(result.num_low_outlier_cells, 25u) << result.message;
}

TEST(Smrf, PointsStackedOnOneSpotSplitLowestFromHighest) {
  // A vertical line of returns (a pole on its own): one cell; the lowest is the ground.
  PointCloud points;
  for (int k = 0; k < 20; ++k) points.emplace_back(3.f, 4.f, 0.5f * k);
  const SmrfResult result = FilterGroundSmrfLocal(points, SmrfOptions{});
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_EQ(result.labels.front(), GroundLabel::kGround);
  EXPECT_EQ(result.labels.back(), GroundLabel::kObject);
  EXPECT_EQ(result.grid_cols, 1);
}

TEST(Smrf, AGridBeyondTheCellLimitIsRefusedWithTheReason) {
  const PointCloud points = {{0, 0, 0}, {1e6f, 1e6f, 0}};
  const SmrfResult result = FilterGroundSmrfLocal(points, SmrfOptions{});
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("max_cells"), std::string::npos) << result.message;
  EXPECT_EQ(result.num_invalid, 2u);
}

TEST(Smrf, ThresholdsCanBeVariedOnOneSurface) {
  const Scene scene = MakeScene(BanksAt(30.f));
  const SmrfSurface surface = ComputeSmrfSurface(scene.points, SmrfOptions{});
  SmrfResult tight, loose;
  ClassifySmrf(scene.points, surface, 0.05, 0.0, &tight);
  ClassifySmrf(scene.points, surface, 1.0, 1.25, &loose);
  EXPECT_LT(tight.num_ground, loose.num_ground);
  EXPECT_EQ(loose.num_ground + loose.num_objects, scene.points.size());
}

}  // namespace
}  // namespace hylo::terrain
