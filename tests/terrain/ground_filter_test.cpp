// Both ground back-ends behind the GroundFilter interface, on synthetic scenes with known
// ground (one parameterised suite), and the bad inputs every back-end must answer clearly.
// SMRF-only scenes (35 deg banks, a bridge deck, low outliers) are in ground_smrf_test.cpp.
#include "hylo/terrain/ground_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "ground_test_scenes.h"

namespace hylo::terrain {
namespace {

using scenes::MakeScene;
using scenes::Scene;
using scenes::SceneScore;
using scenes::SceneSpec;
using scenes::Slab;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

std::vector<Eigen::Vector3d> ToWorld(const PointCloud& points,
                                     const Eigen::Vector3d& shift = Eigen::Vector3d::Zero()) {
  std::vector<Eigen::Vector3d> world;
  for (const Eigen::Vector3f& p : points) world.push_back(p.cast<double>() + shift);
  return world;
}

class GroundBackEnd : public ::testing::TestWithParam<GroundMethod> {
 protected:
  GroundFilterOptions Options() const {
    GroundFilterOptions options;
    options.method = GetParam();
    return options;
  }
  GroundFilterResult Run(const std::vector<Eigen::Vector3d>& points) const {
    return ExtractGround(points, Options());
  }
};

TEST_P(GroundBackEnd, FactoryMakesTheNamedBackEnd) {
  EXPECT_EQ(GroundFilter::Create(Options())->Method(), GetParam());
  const GroundFilterResult result = Run({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  EXPECT_EQ(result.method, GetParam());
  GroundMethod parsed;
  ASSERT_TRUE(ParseGroundMethod(ToString(GetParam()), &parsed));
  EXPECT_EQ(parsed, GetParam());
}

TEST_P(GroundBackEnd, FlatNoisyTerrainIsAllGround) {
  SceneSpec spec;
  spec.size_m = 60.f;
  const Scene scene = MakeScene(spec);
  const GroundFilterResult result = Run(ToWorld(scene.points));
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_GE(scenes::Score(scene, result.labels).ground_kept, 0.999) << result.message;
}

TEST_P(GroundBackEnd, BuildingsOnGentleTerrainAreObjects) {
  SceneSpec spec;
  spec.size_m = 120.f;
  spec.terrain = [](float x, float y) { return 0.05f * x + 0.5f * std::sin(0.05f * y); };
  spec.slabs = {{20, 20, 35, 40, 8}, {60, 70, 80, 82, 5}, {90, 15, 96, 21, 3}};
  const Scene scene = MakeScene(spec);
  const GroundFilterResult result = Run(ToWorld(scene.points));
  ASSERT_TRUE(result.ok) << result.message;
  const SceneScore score = scenes::Score(scene, result.labels);
  EXPECT_GE(score.ground_kept, 0.98) << result.message;
  EXPECT_GE(score.objects_removed, 0.98) << result.message;
  EXPECT_EQ(result.num_ground + result.num_objects, scene.points.size());
}

TEST_P(GroundBackEnd, UtmCoordinatesGiveTheSameLabelsAsNearZero) {
  SceneSpec spec;
  spec.size_m = 80.f;
  spec.slabs = {{20, 20, 35, 40, 8}};
  const Scene scene = MakeScene(spec);
  const GroundFilterResult near_zero = Run(ToWorld(scene.points));
  const GroundFilterResult utm = Run(ToWorld(scene.points, {512345.0, 5412345.0, 312.0}));
  ASSERT_TRUE(near_zero.ok && utm.ok);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < scene.points.size(); ++i) {
    differ += near_zero.labels[i] != utm.labels[i];
  }
  // Float rounding of the shifted coordinates may move a point across a threshold.
  EXPECT_LE(differ, scene.points.size() / 1000);
  EXPECT_NE(utm.origin_world.norm(), 0.0);
}

TEST_P(GroundBackEnd, EmptyAndAllNanCloudsAreReportedNotClassified) {
  const GroundFilterResult empty = Run({});
  EXPECT_FALSE(empty.ok);
  EXPECT_NE(empty.message.find("empty"), std::string::npos) << empty.message;
  const GroundFilterResult nan = Run({{kNan, 0, 0}, {0, kNan, 1}});
  EXPECT_FALSE(nan.ok);
  EXPECT_NE(nan.message.find("finite"), std::string::npos) << nan.message;
  EXPECT_EQ(nan.num_invalid, 2u);
  ASSERT_EQ(nan.labels.size(), 2u);
  EXPECT_EQ(nan.labels[0], GroundLabel::kInvalid);
}

TEST_P(GroundBackEnd, NanPointsAreCountedLabelledAndTheRestClassified) {
  SceneSpec spec;
  spec.size_m = 40.f;
  Scene scene = MakeScene(spec);
  std::vector<Eigen::Vector3d> points = ToWorld(scene.points);
  points[10] = {kNan, 1, 1};
  points[20] = {1, 1, std::numeric_limits<double>::infinity()};
  const GroundFilterResult result = Run(points);
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_EQ(result.num_invalid, 2u);
  EXPECT_EQ(result.labels[10], GroundLabel::kInvalid);
  EXPECT_EQ(result.labels[20], GroundLabel::kInvalid);
  EXPECT_TRUE(std::isnan(result.height_above_ground_m[10]));
  EXPECT_EQ(result.num_ground + result.num_objects + 2, points.size());
  EXPECT_GE(result.num_ground, points.size() - 10);
}

TEST_P(GroundBackEnd, ASinglePointIsGround) {
  const GroundFilterResult result = Run({{5, 5, 100}});
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_EQ(result.labels[0], GroundLabel::kGround);
}

TEST_P(GroundBackEnd, AllPointsOnOneTiltedPlaneAreGround) {
  const float slope = std::tan(20.f * 3.14159265f / 180.f);
  SceneSpec spec;
  spec.size_m = 50.f;
  spec.noise_m = 0.f;
  spec.terrain = [slope](float x, float y) { return slope * (0.8f * x + 0.6f * y); };
  const Scene scene = MakeScene(spec);
  const GroundFilterResult result = Run(ToWorld(scene.points));
  ASSERT_TRUE(result.ok) << result.message;
  // The cloth loses a strip along the upper border (98.9 %); SMRF keeps everything.
  EXPECT_GE(scenes::Score(scene, result.labels).ground_kept, 0.98) << result.message;
}

TEST_P(GroundBackEnd, InvalidOptionsNameTheField) {
  GroundFilterOptions options = Options();
  const bool csf = GetParam() == GroundMethod::kCsf;
  if (csf) {
    options.csf.cloth_resolution_m = -1;
  } else {
    options.smrf.cell_m = -1;
  }
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find(csf ? "csf.cloth_resolution_m" : "smrf.cell_m"), std::string::npos) << why;
  EXPECT_THROW(GroundFilter::Create(options), std::invalid_argument);
}

TEST_P(GroundBackEnd, TheOtherBackEndsOptionsAreCheckedToo) {
  // A configuration is valid whichever method it names: a broken section is reported even
  // when the other back-end runs.
  GroundFilterOptions options = Options();
  if (GetParam() == GroundMethod::kCsf) {
    options.smrf.cell_m = -1;
  } else {
    options.csf.cloth_resolution_m = -1;
  }
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_THROW(GroundFilter::Create(options), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(BothBackEnds, GroundBackEnd,
                         ::testing::Values(GroundMethod::kCsf, GroundMethod::kSmrf),
                         [](const ::testing::TestParamInfo<GroundMethod>& info) {
                           return std::string(ToString(info.param));
                         });

// The defaults are the leave-one-out choices (ground_filter_data_test checks them against the
// choice itself); the robot-map preset differs only in SMRF's elevation threshold.
TEST(GroundFilterOptions, DefaultsAreTheLeaveOneOutChoicesAndValid) {
  const GroundFilterOptions defaults;
  std::string why;
  EXPECT_TRUE(defaults.IsValid(&why)) << why;
  EXPECT_EQ(defaults.method, GroundMethod::kSmrf);
  EXPECT_DOUBLE_EQ(defaults.smrf.max_window_m, LeaveOneOutSmrfOptions().max_window_m);
  EXPECT_DOUBLE_EQ(defaults.csf.cloth_resolution_m, LeaveOneOutCsfOptions().cloth_resolution_m);
  EXPECT_TRUE(LeaveOneOutCsfOptions().IsValid(&why)) << why;
  const GroundFilterOptions robot = GroundFilterOptions::ForRobotMaps();
  EXPECT_TRUE(robot.IsValid(&why)) << why;
  EXPECT_EQ(robot.method, GroundMethod::kSmrf);
  EXPECT_LT(robot.smrf.elevation_threshold_m, defaults.smrf.elevation_threshold_m);
  EXPECT_DOUBLE_EQ(robot.smrf.slope, defaults.smrf.slope);
  EXPECT_DOUBLE_EQ(robot.smrf.elevation_scaler, defaults.smrf.elevation_scaler);
}

TEST(GroundMethod, UnknownNameIsRejected) {
  GroundMethod method = GroundMethod::kCsf;
  EXPECT_FALSE(ParseGroundMethod("pmf", &method));
  EXPECT_FALSE(ParseGroundMethod("", &method));
  EXPECT_EQ(method, GroundMethod::kCsf);
  ClothHoleFill fill = ClothHoleFill::kNearest;
  EXPECT_FALSE(ParseClothHoleFill("sideways", &fill));
  ASSERT_TRUE(ParseClothHoleFill(ToString(ClothHoleFill::kReferenceScanline), &fill));
  EXPECT_EQ(fill, ClothHoleFill::kReferenceScanline);
}

}  // namespace
}  // namespace hylo::terrain
