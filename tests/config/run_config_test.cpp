#include "hylo/config/run_config.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

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
  const std::string dir = std::string(HYLO_SOURCE_DIR) + "/config/presets";
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
  const std::string dir = std::string(HYLO_SOURCE_DIR) + "/config/presets/";
  EXPECT_EQ(LoadRunConfig(dir + "vlp16.yaml").lidar.time_convention,
            logs::PointTimeConvention::kVelodyne);
  EXPECT_EQ(LoadRunConfig(dir + "os1.yaml").lidar.time_convention,
            logs::PointTimeConvention::kOuster);
  EXPECT_EQ(LoadRunConfig(dir + "rs16.yaml").lidar.time_convention,
            logs::PointTimeConvention::kRobosense);
  const RunConfig os1 = LoadRunConfig(dir + "os1.yaml");
  // Ouster's lidar frame is yawed 180 deg from its sensor/IMU frame.
  EXPECT_NEAR(os1.T_imu_lidar.ToIsometry().linear()(0, 0), -1.0, 1e-12);
}

TEST(RunConfig, EmptyFileKeepsDefaults) {
  const RunConfig config = ParseRunConfig("", "empty.yaml");
  EXPECT_EQ(config.BackendName(), "ieskf");
  EXPECT_TRUE(config.pipeline.imu.enabled);
  EXPECT_DOUBLE_EQ(config.pipeline.preprocess.min_range_m, 0.5);
  EXPECT_DOUBLE_EQ(config.pipeline.output.dense_map_voxel_m, 0.1);  // a run's default
}

TEST(RunConfig, MovedKeysSayWhereTheyWent) {
  ExpectConfigError("lidar:\n  min_range_m: 1\n",
                    {"lidar.min_range_m", "moved to preprocess.min_range_m"});
  ExpectConfigError("ieskf:\n  lidar_noise_m: 0.03\n",
                    {"ieskf.lidar_noise_m", "moved to lidar_update.lidar_noise_m"});
  ExpectConfigError("sliding_window:\n  no_imu_yaw_search_deg: 60\n",
                    {"moved to no_imu.yaw_search_deg"});
  ExpectConfigError("ieskf:\n  init_rotation_sigma_rad: 0.02\n",
                    {"moved to initial_uncertainty.rotation_sigma_rad"});
  ExpectConfigError("map:\n  update_after_s: 5\n", {"moved to localization.update_after_s"});
  ExpectConfigError("map:\n  prior_resolution_m: 0.2\n", {"moved to prior_map.resolution_m"});
  ExpectConfigError("lidar:\n  scan_period_s: 0.1\n", {"lidar.scan_period_s", "removed"});
}

TEST(RunConfig, UnknownKeyIsAnErrorNamingItsPath) {
  ExpectConfigError("lidar:\n  topik: /x\n", {"test.yaml", "lidar.topik", "unknown key"});
  ExpectConfigError("imu:\n  noise:\n    gyro_noise: 1\n", {"imu.noise.gyro_noise"});
  ExpectConfigError("bakend: ieskf\n", {"bakend"});
}

TEST(RunConfig, WrongTypeIsAnErrorNamingField) {
  ExpectConfigError("preprocess:\n  min_range_m: near\n",
                    {"preprocess.min_range_m", "expected a number"});
  ExpectConfigError("lidar: 3\n", {"lidar", "expected a map"});
  ExpectConfigError("T_imu_lidar:\n  translation_m: [1, 2]\n",
                    {"T_imu_lidar.translation_m", "3 numbers"});
  ExpectConfigError("lidar:\n  time_convention: sick\n", {"lidar.time_convention", "sick"});
  ExpectConfigError("sliding_window:\n  linear_solver: cg\n",
                    {"sliding_window.linear_solver", "sparse_normal_cholesky", "'cg'"});
  ExpectConfigError("sliding_window:\n  robust_loss: tukey\n",
                    {"sliding_window.robust_loss", "huber", "'tukey'"});
}

TEST(RunConfig, InvalidValueNamesFieldValueAndConstraint) {
  ExpectConfigError("preprocess:\n  min_range_m: 5\n  max_range_m: 2\n",
                    {"preprocess.max_range_m", "2", "> min_range_m"});
  ExpectConfigError("backend: kalman\n", {"backend", "kalman", "ieskf or sliding_window"});
  ExpectConfigError("imu:\n  noise:\n    accel_noise_density: -1\n",
                    {"imu.noise.accel_noise_density", "-1"});
  ExpectConfigError("imu:\n  gravity_mps2: 1.6\n", {"imu.gravity_mps2", "1.6", "[9.7, 9.9]"});
  ExpectConfigError("lidar_update:\n  min_matches: 3\n", {"lidar_update.min_matches", ">= 6"});
  ExpectConfigError("no_imu:\n  yaw_search_deg: 200\n", {"no_imu.yaw_search_deg", "200"});
  ExpectConfigError("initial_uncertainty:\n  rotation_sigma_rad: 0\n",
                    {"initial_uncertainty.rotation_sigma_rad", "> 0"});
  ExpectConfigError("localization:\n  update_after_s: -3\n", {"localization.update_after_s"});
  ExpectConfigError("output:\n  dense_map_voxel_m: 0.001\n", {"output.dense_map_voxel_m"});
  ExpectConfigError("prior_map:\n  tile_load_radius_m: -5\n",
                    {"prior_map", "tile_load_radius_m = -5", ">= 0"});
  ExpectConfigError("prior_map:\n  tile_cache_million_points: 0\n",
                    {"prior_map", "tile_cache_million_points", "> 0"});
  ExpectConfigError("sliding_window:\n  time_offset_prior_sigma_s: 0\n",
                    {"sliding_window.time_offset_prior_sigma_s", "> 0"});
  ExpectConfigError("sliding_window:\n  rematch_threshold: -0.01\n",
                    {"sliding_window.rematch_threshold", "-0.01", ">= 0"});
}

TEST(RunConfig, OnlineCalibrationNeedsTheImuAndNoScanPairs) {
  ExpectConfigError(
      "backend: sliding_window\nimu: none\nsliding_window:\n  estimate_time_offset: true\n",
      {"sliding_window.estimate_time_offset", "needs the IMU"});
  ExpectConfigError("sliding_window:\n  scan_pairs: true\n  estimate_extrinsic_rotation: true\n",
                    {"sliding_window.estimate_time_offset", "scan_pairs: false"});
}

// yaml-cpp keeps both entries of a repeated key and a lookup finds one: the file would say two
// things and the run would silently use one of them.
TEST(RunConfig, KeyGivenTwiceIsAnErrorNamingBothLines) {
  ExpectConfigError("backend: ieskf\nlidar: {topic: /a}\nbackend: sliding_window\n",
                    {"test.yaml", "backend", "given twice", "line 1 and line 3"});
  ExpectConfigError("imu:\n  noise:\n    gyro_noise_density: 1e-4\n"
                    "    accel_noise_density: 1e-3\n    gyro_noise_density: 2e-4\n",
                    {"test.yaml", "imu.noise.gyro_noise_density", "line 3 and line 5"});
  ExpectConfigError("lidar: {topic: /a, topic: /b}\n",
                    {"lidar.topic", "given twice", "line 1, columns 9 and 20"});
  // A repeated unknown key is reported as repeated, before it is reported as unknown.
  ExpectConfigError("preprocess:\n  extra: 1\n  extra: 2\n",
                    {"preprocess.extra", "line 2 and line 3"});
  // Inside a list, as deep as a file nests.
  ExpectConfigError("a: [{b: 1}, {c: 1, c: 2}]\n", {"a[1].c", "given twice"});
}

TEST(RunConfig, SameKeyInDifferentSectionsIsFine) {
  const RunConfig config = ParseRunConfig(
      "lidar: {topic: /points_a}\nimu: {topic: /imu_a}\n"
      "localization:\n  min_inlier_ratio: 0.5\n  icp: {min_inlier_ratio: 0.6}\n",
      "test.yaml");
  EXPECT_EQ(config.lidar.topic, "/points_a");
  EXPECT_EQ(config.imu.topic, "/imu_a");
  EXPECT_DOUBLE_EQ(config.pipeline.localization.min_inlier_ratio, 0.5);
  EXPECT_DOUBLE_EQ(config.pipeline.localization.icp.min_inlier_ratio, 0.6);
}

// An alias can make a node its own child; the duplicate check walks it once and the reader
// reports the key.
TEST(RunConfig, SelfReferencingAliasEndsInAnError) {
  ExpectConfigError("a: &x [*x]\n", {"test.yaml", "unknown key"});
  ExpectConfigError("lidar: &x {topic: /p, more: *x}\n", {"lidar.more", "unknown key"});
}

// The names an enum's error message offers are exactly names the reader takes.
TEST(RunConfig, EnumErrorListsNamesTheReaderTakes) {
  const char* const prefixes[] = {"backend: ",
                                  "lidar:\n  time_convention: ",
                                  "sliding_window:\n  linear_solver: ",
                                  "sliding_window:\n  robust_loss: ",
                                  "ground:\n  method: ",
                                  "ground:\n  csf:\n    hole_fill: "};
  for (const std::string prefix : prefixes) {
    SCOPED_TRACE(prefix);
    std::string message;
    try {
      ParseRunConfig(prefix + "not_a_name\n", "enum.yaml");
    } catch (const ConfigError& e) {
      message = e.what();
    }
    const std::size_t from = message.find("expected "), to = message.find("; got");
    ASSERT_TRUE(from != std::string::npos && to != std::string::npos) << message;
    std::string names = message.substr(from + 9, to - from - 9);  // "a, b or c"
    for (std::size_t at; (at = names.find(" or ")) != std::string::npos;) {
      names.replace(at, 4, ", ");
    }
    std::istringstream list(names);
    int count = 0;
    for (std::string name; std::getline(list >> std::ws, name, ','); ++count) {
      EXPECT_NO_THROW(ParseRunConfig(prefix + name + "\n", "enum.yaml")) << name;
    }
    EXPECT_GE(count, 2) << message;
  }
}

TEST(RunConfig, MalformedYamlIsAnError) {
  ExpectConfigError("lidar: [unclosed\n", {"test.yaml", "malformed YAML"});
}

TEST(RunConfig, ImuNoneDisablesTheImu) {
  const RunConfig config = ParseRunConfig("imu: none\n", "t.yaml");
  EXPECT_FALSE(config.pipeline.imu.enabled);
  EXPECT_TRUE(config.LogOptions().imu_topic.empty());
  EXPECT_NE(ToYaml(config).find("imu: none"), std::string::npos);
}

TEST(RunConfig, EffectiveConfigurationRoundTrips) {
  RunConfig config;
  config.pipeline.estimator.backend = estimation::Estimator::Backend::kSlidingWindow;
  config.pipeline.estimator.sliding_window.linear_solver =
      estimation::SlidingWindowOptions::LinearSolver::kDenseSchur;
  config.pipeline.estimator.sliding_window.robust_loss =
      estimation::SlidingWindowOptions::RobustLoss::kCauchy;
  config.pipeline.estimator.no_imu.yaw_search_deg = 45.0;
  config.pipeline.initial_uncertainty.localized_position_sigma_m = 0.2;
  config.lidar.topic = "/velodyne_points";
  config.lidar.time_convention = logs::PointTimeConvention::kOuster;
  config.pipeline.lidar.time_offset_s = -0.0125;
  config.pipeline.imu.accel_range_mps2 = 78.45;
  config.pipeline.imu.gyro_range_radps = 8.7;
  config.pipeline.preprocess.max_range_m = 80.5;
  config.pipeline.imu.noise.gyro_noise_density = 1.25e-4;
  config.prior_map.resolution_m = 0.25;
  config.initial_guess = "1 2 3 0 0 90";
  config.T_imu_lidar.translation_m = {0.1, -0.2, 0.3};
  config.T_imu_lidar.rotation_rpy_deg = {1.5, -2.0, 90.0};
  const RunConfig back = ParseRunConfig(ToYaml(config), "roundtrip");
  EXPECT_EQ(back.BackendName(), "sliding_window");
  EXPECT_EQ(back.pipeline.estimator.sliding_window.linear_solver,
            estimation::SlidingWindowOptions::LinearSolver::kDenseSchur);
  EXPECT_EQ(back.pipeline.estimator.sliding_window.robust_loss,
            estimation::SlidingWindowOptions::RobustLoss::kCauchy);
  EXPECT_DOUBLE_EQ(back.pipeline.estimator.no_imu.yaw_search_deg, 45.0);
  EXPECT_DOUBLE_EQ(back.pipeline.initial_uncertainty.localized_position_sigma_m, 0.2);
  EXPECT_EQ(back.lidar.topic, config.lidar.topic);
  EXPECT_EQ(back.lidar.time_convention, config.lidar.time_convention);
  EXPECT_DOUBLE_EQ(back.pipeline.lidar.time_offset_s, -0.0125);
  EXPECT_DOUBLE_EQ(back.pipeline.imu.accel_range_mps2, 78.45);
  EXPECT_DOUBLE_EQ(back.pipeline.imu.gyro_range_radps, 8.7);
  EXPECT_DOUBLE_EQ(back.pipeline.preprocess.max_range_m, 80.5);
  EXPECT_DOUBLE_EQ(back.pipeline.imu.noise.gyro_noise_density, 1.25e-4);
  EXPECT_DOUBLE_EQ(back.prior_map.resolution_m, 0.25);
  EXPECT_EQ(back.initial_guess, "1 2 3 0 0 90");
  EXPECT_TRUE(back.T_imu_lidar.translation_m.isApprox(config.T_imu_lidar.translation_m));
  EXPECT_TRUE(back.T_imu_lidar.ToIsometry().isApprox(config.T_imu_lidar.ToIsometry(), 1e-9));
}

TEST(RunConfig, SavedFileLoadsBack) {
  const std::string dir = hylo::testing::ScratchDir("run_config");
  RunConfig config;
  config.pipeline.imu.enabled = false;
  SaveRunConfig(dir + "/effective.yaml", config);
  EXPECT_FALSE(LoadRunConfig(dir + "/effective.yaml").pipeline.imu.enabled);
  EXPECT_THROW(LoadRunConfig(dir + "/missing.yaml"), ConfigError);
}

TEST(TransformConfig, RollPitchYawComposeAsZYX) {
  // R = Rz(yaw) Ry(pitch) Rx(roll), written out element by element: with all three angles
  // non-zero every other order of composition gives a different matrix.
  const double r = 30.0 * M_PI / 180.0, p = 45.0 * M_PI / 180.0, y = 60.0 * M_PI / 180.0;
  const double cr = std::cos(r), sr = std::sin(r), cp = std::cos(p), sp = std::sin(p);
  const double cy = std::cos(y), sy = std::sin(y);
  Eigen::Matrix3d expected;
  expected << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,          //
      -sp, cp * sr, cp * cr;
  TransformConfig t;
  t.rotation_rpy_deg = {30.0, 45.0, 60.0};
  t.translation_m = {1.0, 2.0, 3.0};
  EXPECT_TRUE(t.ToIsometry().linear().isApprox(expected, 1e-12)) << t.ToIsometry().linear();
  EXPECT_TRUE(t.ToIsometry().translation().isApprox(Eigen::Vector3d(1.0, 2.0, 3.0)));
}

TEST(RunConfig, OdometrySectionsParseValidateAndRoundTrip) {
  const RunConfig config = ParseRunConfig(
      "preprocess: {scan_voxel_m: 0.4, point_stride: 3}\n"
      "ieskf: {max_iterations: 6, online_extrinsic: true}\n"
      "planes: {planarity_threshold_m: 0.05}\n"
      "map: {voxel_size_m: 0.3, window_size_m: 0}\n"
      "init: {duration_s: 2.0}\n"
      "standstill: {enabled: false, max_spread_ratio: 4}\n"
      "T_imu_lidar: {translation_m: [0, 0, 0.2], rotation_rpy_deg: [0, 0, 180]}\n",
      "test.yaml");
  const odometry::OdometryPipelineOptions& p = config.pipeline;
  EXPECT_DOUBLE_EQ(p.preprocess.scan_voxel_m, 0.4);
  EXPECT_EQ(p.preprocess.point_stride, 3);
  EXPECT_EQ(p.estimator.ieskf.max_iterations, 6);
  EXPECT_TRUE(p.estimator.ieskf.online_extrinsic);
  const RunConfig back = ParseRunConfig(ToYaml(config), "saved.yaml");
  EXPECT_DOUBLE_EQ(back.pipeline.planes.planarity_threshold_m, 0.05);
  EXPECT_DOUBLE_EQ(back.pipeline.map.voxel_size_m, 0.3);
  EXPECT_DOUBLE_EQ(back.pipeline.map.window_size_m, 0.0);
  EXPECT_DOUBLE_EQ(back.pipeline.init.duration_s, 2.0);
  EXPECT_FALSE(back.pipeline.estimator.standstill.enabled);
  EXPECT_DOUBLE_EQ(back.pipeline.estimator.standstill.max_spread_ratio, 4.0);
  const odometry::OdometryPipelineOptions pipeline = back.PipelineOptions();
  std::string why;
  EXPECT_TRUE(pipeline.IsValid(&why)) << why;
  EXPECT_EQ(pipeline.estimator.ieskf.max_iterations, 6);
  // The one field the pipeline takes from elsewhere: the extrinsic, from its YAML form.
  EXPECT_TRUE(pipeline.T_imu_lidar.translation().isApprox(Eigen::Vector3d(0, 0, 0.2)));
  EXPECT_NEAR(pipeline.T_imu_lidar.so3().Matrix()(0, 0), -1.0, 1e-12);
}

TEST(RunConfig, OdometrySectionsRejectUnknownKeysAndBadValues) {
  ExpectConfigError("ieskf: {max_iteration: 3}\n", {"ieskf.max_iteration"});
  ExpectConfigError("ieskf: {max_iterations: 0}\n", {"ieskf.max_iterations", ">= 1"});
  ExpectConfigError("planes: {num_neighbors: 2}\n", {"planes.num_neighbors"});
  ExpectConfigError("map: {voxel_size_m: -1}\n", {"map.voxel_size_m"});
  ExpectConfigError("preprocess: {point_stride: 0}\n", {"preprocess.point_stride", ">= 1"});
  ExpectConfigError("standstill: {max_speed_mps: 0}\n", {"standstill.max_speed_mps", "> 0"});
}

// The ground section: the robot-map preset by default, the method and each back-end's
// options read, validated and written back.
TEST(RunConfig, GroundSectionParsesValidatesAndRoundTrips) {
  const RunConfig defaults = ParseRunConfig("", "empty.yaml");
  EXPECT_EQ(defaults.ground.method, terrain::GroundMethod::kSmrf);
  EXPECT_DOUBLE_EQ(defaults.ground.smrf.elevation_threshold_m,
                   terrain::GroundFilterOptions::ForRobotMaps().smrf.elevation_threshold_m);
  const RunConfig config = ParseRunConfig(
      "ground:\n  method: csf\n  csf: {rigidness: 2, hole_fill: reference}\n"
      "  smrf: {cell_m: 0.5, max_window_m: 12}\n",
      "test.yaml");
  EXPECT_EQ(config.ground.method, terrain::GroundMethod::kCsf);
  EXPECT_EQ(config.ground.csf.rigidness, 2);
  EXPECT_EQ(config.ground.csf.hole_fill, terrain::ClothHoleFill::kReferenceScanline);
  const RunConfig back = ParseRunConfig(ToYaml(config), "saved.yaml");
  EXPECT_EQ(back.ground.method, terrain::GroundMethod::kCsf);
  EXPECT_EQ(back.ground.csf.hole_fill, terrain::ClothHoleFill::kReferenceScanline);
  EXPECT_DOUBLE_EQ(back.ground.smrf.cell_m, 0.5);
  EXPECT_DOUBLE_EQ(back.ground.smrf.max_window_m, 12.0);
  ExpectConfigError("ground: {method: pmf}\n", {"ground.method", "smrf or csf"});
  ExpectConfigError("ground: {smrf: {cell: 1}}\n", {"ground.smrf.cell", "unknown key"});
  ExpectConfigError("ground: {smrf: {cell_m: -1}}\n", {"ground.smrf.cell_m = -1"});
  // The back-end not chosen is checked too: a file is valid whichever method it picks.
  ExpectConfigError("ground: {method: smrf, csf: {rigidness: 0}}\n", {"ground.csf.rigidness"});
  ExpectConfigError("ground: {csf: {hole_fill: sideways}}\n", {"ground.csf.hole_fill"});
}

// The inspection section: the planner's defaults, every sub-section read, validated and written
// back.
TEST(RunConfig, InspectionSectionParsesValidatesAndRoundTrips) {
  const RunConfig defaults = ParseRunConfig("", "empty.yaml");
  const inspection::InspectionOptions library;
  EXPECT_DOUBLE_EQ(defaults.inspection.visibility.camera_height_m,
                   library.visibility.camera_height_m);
  EXPECT_DOUBLE_EQ(defaults.inspection.visibility.occupancy.clearance_m,
                   library.visibility.occupancy.clearance_m);
  const RunConfig config = ParseRunConfig(
      "inspection:\n  visibility: {camera_height_m: 1.5, max_range_m: 20,\n"
      "    occupancy: {voxel_size_m: 0.2, clearance_m: 0.3}}\n"
      "  search: {robot_radius_m: 0.5}\n  viewpoint: {preferred_range_m: 8}\n"
      "  tour: {return_to_start: false, exact_max_stops: 10}\n  start_snap_radius_m: 1\n",
      "test.yaml");
  const RunConfig back = ParseRunConfig(ToYaml(config), "saved.yaml");
  for (const RunConfig* c : {&config, &back}) {
    const inspection::InspectionOptions& o = c->inspection;
    EXPECT_DOUBLE_EQ(o.visibility.camera_height_m, 1.5);
    EXPECT_DOUBLE_EQ(o.visibility.max_range_m, 20.0);
    EXPECT_DOUBLE_EQ(o.visibility.occupancy.voxel_size_m, 0.2);
    EXPECT_DOUBLE_EQ(o.visibility.occupancy.clearance_m, 0.3);
    EXPECT_DOUBLE_EQ(o.search.robot_radius_m, 0.5);
    EXPECT_DOUBLE_EQ(o.viewpoint.preferred_range_m, 8.0);
    EXPECT_FALSE(o.tour.return_to_start);
    EXPECT_EQ(o.tour.exact_max_stops, 10);
    EXPECT_DOUBLE_EQ(o.start_snap_radius_m, 1.0);
  }
  ExpectConfigError("inspection: {visibility: {camera_hight_m: 1}}\n",
                    {"inspection.visibility.camera_hight_m", "unknown key"});
  ExpectConfigError("inspection: {visibility: {min_range_m: 30}}\n",
                    {"inspection.visibility.min_range_m = 30", "max_range_m"});
  ExpectConfigError("inspection: {visibility: {occupancy: {voxel_size_m: 0}}}\n",
                    {"inspection.visibility.occupancy.voxel_size_m = 0"});
  ExpectConfigError("inspection: {tour: {exact_max_stops: 40}}\n",
                    {"inspection.tour.exact_max_stops = 40"});
}

}  // namespace
}  // namespace hylo::config
