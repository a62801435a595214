#include "hylo/config/run_config.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_data.h"

namespace hylo::config {
namespace {

// Expects ParseRunConfig to throw a ConfigError whose message contains every fragment.
void ExpectConfigError(const std::string& yaml, std::initializer_list<const char*> fragments) {
  try {
    ParseRunConfig(yaml, "test.yaml");
    FAIL() << "expected a ConfigError for:\n" << yaml;
  } catch (const ConfigError& e) {
    for (const char* f : fragments) {
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos)
          << "message '" << e.what() << "' lacks '" << f << "'";
    }
  }
}

TEST(RunConfig, EveryPresetLoadsAndIsValid) {
  const std::string dir = std::string(HYLO_SOURCE_DIR) + "/config";
  int presets = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const RunConfig config = LoadRunConfig(entry.path().string());
    std::string why;
    EXPECT_TRUE(config.IsValid(&why)) << why;
    ++presets;
  }
  EXPECT_GE(presets, 5) << "presets for VLP-16, RS-16, OS1, XT32 and Livox are expected";
}

TEST(RunConfig, PresetsSetTheirDriversTimeConvention) {
  const std::string dir = std::string(HYLO_SOURCE_DIR) + "/config/";
  EXPECT_EQ(LoadRunConfig(dir + "vlp16.yaml").lidar.time_convention,
            io::PointTimeConvention::kVelodyne);
  EXPECT_EQ(LoadRunConfig(dir + "os1.yaml").lidar.time_convention,
            io::PointTimeConvention::kOuster);
  EXPECT_EQ(LoadRunConfig(dir + "rs16.yaml").lidar.time_convention,
            io::PointTimeConvention::kRobosense);
  const RunConfig os1 = LoadRunConfig(dir + "os1.yaml");
  // Ouster's lidar frame is yawed 180 deg from its sensor/IMU frame.
  EXPECT_NEAR(os1.T_imu_lidar.ToIsometry().linear()(0, 0), -1.0, 1e-12);
}

TEST(RunConfig, EmptyFileKeepsDefaults) {
  const RunConfig config = ParseRunConfig("", "empty.yaml");
  EXPECT_EQ(config.backend, "ieskf");
  EXPECT_TRUE(config.imu.enabled);
  EXPECT_DOUBLE_EQ(config.lidar.scan_period_s, 0.1);
}

TEST(RunConfig, UnknownKeyIsAnErrorNamingItsPath) {
  ExpectConfigError("lidar:\n  topik: /x\n", {"test.yaml", "lidar.topik", "unknown key"});
  ExpectConfigError("imu:\n  noise:\n    gyro_noise: 1\n", {"imu.noise.gyro_noise"});
  ExpectConfigError("bakend: ieskf\n", {"bakend"});
}

TEST(RunConfig, WrongTypeIsAnErrorNamingField) {
  ExpectConfigError("lidar:\n  min_range_m: near\n", {"lidar.min_range_m", "expected a number"});
  ExpectConfigError("lidar: 3\n", {"lidar", "expected a map"});
  ExpectConfigError("T_imu_lidar:\n  translation_m: [1, 2]\n",
                    {"T_imu_lidar.translation_m", "3 numbers"});
  ExpectConfigError("lidar:\n  time_convention: sick\n", {"lidar.time_convention", "sick"});
}

TEST(RunConfig, InvalidValueNamesFieldValueAndConstraint) {
  ExpectConfigError("lidar:\n  min_range_m: 5\n  max_range_m: 2\n",
                    {"lidar.max_range_m", "2", "> min_range_m"});
  ExpectConfigError("backend: kalman\n", {"backend", "kalman", "ieskf or sliding_window"});
  ExpectConfigError("imu:\n  noise:\n    accel_noise_density: -1\n",
                    {"imu.noise.accel_noise_density", "-1"});
  ExpectConfigError("imu:\n  gravity_mps2: 1.6\n", {"imu.gravity_mps2", "1.6"});
}

TEST(RunConfig, MalformedYamlIsAnError) {
  ExpectConfigError("lidar: [unclosed\n", {"test.yaml", "malformed YAML"});
}

TEST(RunConfig, ImuNoneDisablesTheImu) {
  const RunConfig config = ParseRunConfig("imu: none\n", "t.yaml");
  EXPECT_FALSE(config.imu.enabled);
  EXPECT_TRUE(config.LogOptions().imu_topic.empty());
  EXPECT_NE(ToYaml(config).find("imu: none"), std::string::npos);
}

TEST(RunConfig, EffectiveConfigurationRoundTrips) {
  RunConfig config;
  config.backend = "sliding_window";
  config.lidar.topic = "/velodyne_points";
  config.lidar.time_convention = io::PointTimeConvention::kOuster;
  config.lidar.max_range_m = 80.5;
  config.imu.noise.gyro_noise_density = 1.25e-4;
  config.T_imu_lidar.translation_m = {0.1, -0.2, 0.3};
  config.T_imu_lidar.rotation_rpy_deg = {1.5, -2.0, 90.0};
  const RunConfig back = ParseRunConfig(ToYaml(config), "roundtrip");
  EXPECT_EQ(back.backend, config.backend);
  EXPECT_EQ(back.lidar.topic, config.lidar.topic);
  EXPECT_EQ(back.lidar.time_convention, config.lidar.time_convention);
  EXPECT_DOUBLE_EQ(back.lidar.max_range_m, 80.5);
  EXPECT_DOUBLE_EQ(back.imu.noise.gyro_noise_density, 1.25e-4);
  EXPECT_TRUE(back.T_imu_lidar.translation_m.isApprox(config.T_imu_lidar.translation_m));
  EXPECT_TRUE(back.T_imu_lidar.ToIsometry().isApprox(config.T_imu_lidar.ToIsometry(), 1e-9));
}

TEST(RunConfig, SavedFileLoadsBack) {
  const std::string dir = hylo::testing::ScratchDir("run_config");
  RunConfig config;
  config.imu.enabled = false;
  SaveRunConfig(dir + "/effective.yaml", config);
  EXPECT_FALSE(LoadRunConfig(dir + "/effective.yaml").imu.enabled);
  EXPECT_THROW(LoadRunConfig(dir + "/missing.yaml"), ConfigError);
}

TEST(TransformConfig, RollPitchYawComposeAsZYX) {
  TransformConfig t;
  t.rotation_rpy_deg = {0.0, 0.0, 90.0};
  const Eigen::Vector3d x_rotated = t.ToIsometry().linear() * Eigen::Vector3d::UnitX();
  EXPECT_TRUE(x_rotated.isApprox(Eigen::Vector3d::UnitY(), 1e-12));
}

TEST(RunConfig, OdometrySectionsParseValidateAndRoundTrip) {
  const RunConfig config = ParseRunConfig(
      "preprocess: {scan_voxel_m: 0.4, point_stride: 3}\n"
      "ieskf: {max_iterations: 6, online_extrinsic: true}\n"
      "planes: {planarity_threshold_m: 0.05}\n"
      "map: {voxel_size_m: 0.3, window_size_m: 0}\n"
      "init: {duration_s: 2.0}\n",
      "test.yaml");
  EXPECT_DOUBLE_EQ(config.preprocess.scan_voxel_m, 0.4);
  EXPECT_EQ(config.preprocess.point_stride, 3);
  EXPECT_EQ(config.ieskf.max_iterations, 6);
  EXPECT_TRUE(config.ieskf.online_extrinsic);
  const RunConfig back = ParseRunConfig(ToYaml(config), "saved.yaml");
  EXPECT_DOUBLE_EQ(back.planes.planarity_threshold_m, 0.05);
  EXPECT_DOUBLE_EQ(back.map.voxel_size_m, 0.3);
  EXPECT_DOUBLE_EQ(back.map.window_size_m, 0.0);
  EXPECT_DOUBLE_EQ(back.init.duration_s, 2.0);
  const estimation::OdometryPipelineOptions pipeline = back.PipelineOptions();
  std::string why;
  EXPECT_TRUE(pipeline.IsValid(&why)) << why;
  EXPECT_EQ(pipeline.estimator.ieskf.max_iterations, 6);
  EXPECT_DOUBLE_EQ(pipeline.preprocess.max_range_m, back.lidar.max_range_m);
}

TEST(RunConfig, OdometrySectionsRejectUnknownKeysAndBadValues) {
  ExpectConfigError("ieskf: {max_iteration: 3}\n", {"ieskf.max_iteration"});
  ExpectConfigError("ieskf: {max_iterations: 0}\n", {"ieskf.max_iterations", ">= 1"});
  ExpectConfigError("planes: {num_neighbors: 2}\n", {"planes.num_neighbors"});
  ExpectConfigError("map: {voxel_size_m: -1}\n", {"map.voxel_size_m"});
  ExpectConfigError("preprocess: {point_stride: 0}\n", {"preprocess.point_stride", ">= 1"});
}

// The ground section: the robot-map preset by default, the method and each back-end's
// options read, validated and written back.
TEST(RunConfig, GroundSectionParsesValidatesAndRoundTrips) {
  const RunConfig defaults = ParseRunConfig("", "empty.yaml");
  EXPECT_EQ(defaults.ground.method, mapping::GroundMethod::kSmrf);
  EXPECT_DOUBLE_EQ(defaults.ground.smrf.elevation_threshold_m,
                   mapping::GroundFilterOptions::ForRobotMaps().smrf.elevation_threshold_m);
  const RunConfig config = ParseRunConfig(
      "ground:\n  method: csf\n  csf: {rigidness: 2, hole_fill: reference}\n"
      "  smrf: {cell_m: 0.5, max_window_m: 12}\n",
      "test.yaml");
  EXPECT_EQ(config.ground.method, mapping::GroundMethod::kCsf);
  EXPECT_EQ(config.ground.csf.rigidness, 2);
  EXPECT_EQ(config.ground.csf.hole_fill, mapping::ClothHoleFill::kReferenceScanline);
  const RunConfig back = ParseRunConfig(ToYaml(config), "saved.yaml");
  EXPECT_EQ(back.ground.method, mapping::GroundMethod::kCsf);
  EXPECT_EQ(back.ground.csf.hole_fill, mapping::ClothHoleFill::kReferenceScanline);
  EXPECT_DOUBLE_EQ(back.ground.smrf.cell_m, 0.5);
  EXPECT_DOUBLE_EQ(back.ground.smrf.max_window_m, 12.0);
  ExpectConfigError("ground: {method: pmf}\n", {"ground.method", "smrf or csf"});
  ExpectConfigError("ground: {smrf: {cell: 1}}\n", {"ground.smrf.cell", "unknown key"});
  ExpectConfigError("ground: {smrf: {cell_m: -1}}\n", {"ground", "cell_m = -1"});
  ExpectConfigError("ground: {csf: {hole_fill: sideways}}\n", {"ground.csf.hole_fill"});
}

TEST(RunConfig, ImuNoneSelectsTheNoImuPipeline) {
  const RunConfig config = ParseRunConfig("imu: none\n", "test.yaml");
  EXPECT_FALSE(config.PipelineOptions().estimator.use_imu);
}

}  // namespace
}  // namespace hylo::config
