// The back-ends' online calibration on randomized scenarios, each configured from its sensor
// sheet and localized for 35 s in a map of its mapping drive's scans at their true poses.
// The smoother (sliding_window.estimate_*):
//   - with a 20 ms clock offset and a 1° extrinsic rotation left out of the configuration,
//     the window must find the offset within 4 ms and bring the rotation within 0.5°: the
//     worst of twelve scenarios, rounded up (the targets, 2 ms and 0.2°, are missed on some of
//     them: docs/results.md);
//   - with the configuration right, it must not wander off it (the same bounds).
// The truth is the scenario's own clock offset and extrinsic; the sheet rounds them to 1 ms
// and 0.1°, which the window sees. Scenarios 3, 6, 8, 9 and 10 were used while the
// calibration was developed; these are two of the others, the two cheapest to simulate.
// The filter (ieskf.online_extrinsic, which has no clock offset to estimate): the same 1°
// rotation, the same bounds, on the same two scenarios; nothing was tuned for it (its figures
// on all 24 scenarios are in docs/results.md, two of which miss these bounds); and on
// scenario 0, whose start comes from a search while moving, with the calibration held then.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>

#include "estimation/scenario_run.h"
#include "hylo/common/time.h"
#include "hylo/lie/so3.h"
#include "hylo/run/run_log.h"

namespace hylo::testing {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kClockError_s = 0.020;
const Eigen::Vector3d kRotationError_rad =
    1.0 * kDeg * Eigen::Vector3d(1.0, -1.0, 1.0).normalized();

struct CalibrationErrors {
  double time_offset_s = 0.0;  ///< estimated minus true correction
  double time_offset_sigma_s = 0.0;
  double rotation_deg = 0.0;  ///< angle between the estimated and the true extrinsic rotation
  Eigen::Vector3d rotation_vehicle_deg = Eigen::Vector3d::Zero();  ///< as roll, pitch, yaw
  double rotation_sigma_deg = 0.0;                                 ///< largest of the three
  double ate_m = 0.0;
};

// The scenario drawn for `number` with a 40 s mapping drive and a 35 s drive B.
sim::Scenario CalibrationScenario(uint64_t number) {
  sim::Scenario scenario = sim::DrawScenario(number);
  scenario.max_drive_a_s = 40.0;
  scenario.max_drive_b_s = 35.0;
  return scenario;
}

// Drive B localized by `backend` in the true-pose map of the mapping drive, the options as the
// sheet gives them then changed by `adjust`: that one run's figures (`summary`: the scenario's).
ModeFigures LocalizeAdjusted(const sim::Scenario& scenario, estimation::Estimator::Backend backend,
                             std::function<void(odometry::OdometryPipelineOptions*)> adjust,
                             std::string* summary) {
  ScenarioRunOptions options;
  options.preset_dir = std::string(HYLO_SOURCE_DIR) + "/config/presets";
  options.slam = false;
  options.backends = {backend};
  Variant wrong;
  wrong.name = "calibrating";
  wrong.adjust = std::move(adjust);
  options.variants = {wrong};
  const ScenarioFigures f = RunScenario(scenario, options);
  *summary = f.summary;
  EXPECT_EQ(f.runs.size(), 1u);
  const ModeFigures run = f.runs.at(0).localization;
  EXPECT_FALSE(run.failed) << run.message;
  return run;
}

// The rotation from the scenario's true extrinsic rotation to the one `c` estimated, as a
// rotation vector about the vehicle's axes (x forward, z up: roll, pitch, yaw), deg. Its norm
// is the angle between the two; its axes say which motion the estimate lacked.
Eigen::Vector3d RotationErrorDeg(const sim::Scenario& scenario,
                                 const lie::SO3d& R_imu_lidar_configured,
                                 const estimation::OnlineCalibration& c) {
  const lie::SO3d R_true = lie::SO3d::FromMatrix(scenario.T_imu_lidar.linear());
  const lie::SO3d Q_true = R_true * R_imu_lidar_configured.Inverse();
  const lie::SO3d Q_estimated = lie::SO3d::Exp(c.extrinsic_rotation_correction_rad);
  // Q left of R_imu_lidar: the error is about the IMU's axes.
  return scenario.R_vehicle_imu * lie::Minus(Q_estimated, Q_true) / kDeg;
}

// Runs drive B in the true-pose map with calibration on, the configuration wrong by
// `clock_error_s` and `rotation_error_rad` (0 and zero: right, as far as the sheet knows).
CalibrationErrors Calibrate(uint64_t number, double clock_error_s,
                            const Eigen::Vector3d& rotation_error_rad) {
  const sim::Scenario scenario = CalibrationScenario(number);
  lie::SO3d R_imu_lidar_configured;
  double configured_offset_s = 0.0;
  std::string summary;
  const ModeFigures run = LocalizeAdjusted(
      scenario, estimation::Estimator::Backend::kSlidingWindow,
      [&](odometry::OdometryPipelineOptions* o) {
        // No wall-time stop of the solve: the figures must not depend on the machine's load.
        o->estimator.sliding_window.max_solver_time_s = 1.0;
        o->lidar.time_offset_s -= clock_error_s;
        o->T_imu_lidar.so3() = lie::SO3d::Exp(rotation_error_rad) * o->T_imu_lidar.so3();
        o->estimator.sliding_window.estimate_time_offset = true;
        o->estimator.sliding_window.estimate_extrinsic_rotation = true;
        R_imu_lidar_configured = o->T_imu_lidar.so3();
        configured_offset_s = o->lidar.time_offset_s;
      },
      &summary);
  const estimation::OnlineCalibration& c = run.calibration;
  EXPECT_TRUE(c.time_offset_estimated && c.extrinsic_rotation_estimated);

  // t_imu = t_lidar − lidar_time_offset: the offset a configuration needs.
  const double true_offset_s = -NanosToSeconds(scenario.lidar_time_offset_ns);
  CalibrationErrors e;
  e.time_offset_s = c.time_offset_correction_s - (true_offset_s - configured_offset_s);
  e.time_offset_sigma_s = c.time_offset_sigma_s;
  e.rotation_vehicle_deg = RotationErrorDeg(scenario, R_imu_lidar_configured, c);
  e.rotation_deg = e.rotation_vehicle_deg.norm();
  e.rotation_sigma_deg = c.extrinsic_rotation_sigma_rad.maxCoeff() / kDeg;
  e.ate_m = run.ate_m;
  std::printf(
      "scenario %llu (%s): time offset error %+.2f ms (sigma %.2f ms), rotation error %.3f deg "
      "(roll %+.3f, pitch %+.3f, yaw %+.3f; sigma %.3f deg), correction found %+.2f ms, %.3f "
      "deg; ATE %.3f m\n",
      static_cast<unsigned long long>(number), summary.c_str(), e.time_offset_s * 1e3,
      e.time_offset_sigma_s * 1e3, e.rotation_deg, e.rotation_vehicle_deg.x(),
      e.rotation_vehicle_deg.y(), e.rotation_vehicle_deg.z(), e.rotation_sigma_deg,
      c.time_offset_correction_s * 1e3, c.extrinsic_rotation_correction_rad.norm() / kDeg, e.ate_m);
  return e;
}

class OnlineCalibration : public ::testing::TestWithParam<uint64_t> {};

TEST_P(OnlineCalibration, FindsAClockOffsetAndAnExtrinsicRotationLeftOutOfTheConfiguration) {
  const CalibrationErrors e = Calibrate(GetParam(), kClockError_s, kRotationError_rad);
  EXPECT_LE(std::abs(e.time_offset_s), 0.004);
  EXPECT_LE(e.rotation_deg, 0.5);
  EXPECT_LE(e.ate_m, 0.03);
}

TEST(OnlineCalibration, StaysNearARightConfiguration) {
  const CalibrationErrors e = Calibrate(12, 0.0, Eigen::Vector3d::Zero());
  EXPECT_LE(std::abs(e.time_offset_s), 0.004);
  EXPECT_LE(e.rotation_deg, 0.5);
  EXPECT_LE(e.ate_m, 0.03);
}

TEST(OnlineCalibration, SummaryGivesTheOffsetToConfigureAndDegrees) {
  estimation::OnlineCalibration c;
  c.time_offset_estimated = true;
  c.time_offset_correction_s = 0.02;
  c.time_offset_sigma_s = 0.001;
  const io::Json time_only = run::OnlineCalibrationJson(c, -0.005);
  EXPECT_NEAR(time_only.at("lidar_time_offset_s").get<double>(), 0.015, 1e-12);
  EXPECT_NEAR(time_only.at("time_offset_sigma_s").get<double>(), 0.001, 1e-12);
  EXPECT_FALSE(time_only.contains("extrinsic_rotation_correction_deg"));
  c.extrinsic_rotation_estimated = true;
  c.extrinsic_rotation_correction_rad = Eigen::Vector3d(0.0, 0.0, -kDeg);
  const io::Json both = run::OnlineCalibrationJson(c, 0.0);
  EXPECT_NEAR(both.at("extrinsic_rotation_correction_deg").at(2).get<double>(), -1.0, 1e-12);
  io::Json summary;
  EXPECT_EQ(run::OnlineCalibrationLine(summary), "");
  summary["online_calibration"] = both;
  EXPECT_NE(
      run::OnlineCalibrationLine(summary).find("lidar.time_offset_s 0.0200 s (correction +20.0 ms"),
      std::string::npos)
      << run::OnlineCalibrationLine(summary);
  EXPECT_NE(run::OnlineCalibrationLine(summary).find("[0.00, 0.00, -1.00] deg"), std::string::npos);
  // The IESKF's extrinsic: rotation and translation, without a clock offset.
  estimation::OnlineCalibration extrinsic;
  extrinsic.extrinsic_rotation_estimated = true;
  extrinsic.extrinsic_translation_estimated = true;
  extrinsic.extrinsic_translation_correction_m = Eigen::Vector3d(0.0, 0.012, 0.0);
  extrinsic.extrinsic_translation_sigma_m = Eigen::Vector3d(0.004, 0.004, 0.006);
  summary["online_calibration"] = run::OnlineCalibrationJson(extrinsic, 0.0);
  EXPECT_FALSE(summary["online_calibration"].contains("lidar_time_offset_s"));
  const std::string line = run::OnlineCalibrationLine(summary);
  EXPECT_NE(line.find("optimistic): extrinsic rotation correction [0.00, 0.00, 0.00] deg"),
            std::string::npos)
      << line;
  EXPECT_NE(line.find("; extrinsic translation correction [0.000, 0.012, 0.000] m (sigma [0.004, "
                      "0.004, 0.006])"),
            std::string::npos)
      << line;
}

// The IESKF's online extrinsic (ieskf.online_extrinsic) on drive B in the true-pose map, the
// configured rotation wrong by `rotation_error_rad`: the errors left in its estimate.
struct ExtrinsicErrors {
  double rotation_deg = 0.0;  ///< angle between the estimated and the true rotation
  Eigen::Vector3d rotation_vehicle_deg = Eigen::Vector3d::Zero();  ///< as roll, pitch, yaw
  double rotation_sigma_deg = 0.0;                                 ///< largest of the three
  double translation_m = 0.0;        ///< distance between the estimated and the true translation
  double translation_sigma_m = 0.0;  ///< largest of the three
  double ate_m = 0.0;
  std::size_t searches = 0;  ///< searches while moving the run began
};

ExtrinsicErrors IeskfCalibrate(uint64_t number, const Eigen::Vector3d& rotation_error_rad) {
  const sim::Scenario scenario = CalibrationScenario(number);
  lie::SE3d T_imu_lidar_configured;
  std::string summary;
  const ModeFigures run = LocalizeAdjusted(
      scenario, estimation::Estimator::Backend::kIeskf,
      [&](odometry::OdometryPipelineOptions* o) {
        o->T_imu_lidar.so3() = lie::SO3d::Exp(rotation_error_rad) * o->T_imu_lidar.so3();
        o->estimator.ieskf.online_extrinsic = true;
        T_imu_lidar_configured = o->T_imu_lidar;
      },
      &summary);
  const estimation::OnlineCalibration& c = run.calibration;
  EXPECT_TRUE(c.extrinsic_rotation_estimated && c.extrinsic_translation_estimated);
  EXPECT_FALSE(c.time_offset_estimated);
  ExtrinsicErrors e;
  e.rotation_vehicle_deg = RotationErrorDeg(scenario, T_imu_lidar_configured.so3(), c);
  e.rotation_deg = e.rotation_vehicle_deg.norm();
  e.rotation_sigma_deg = c.extrinsic_rotation_sigma_rad.maxCoeff() / kDeg;
  e.translation_m = (T_imu_lidar_configured.translation() + c.extrinsic_translation_correction_m -
                     scenario.T_imu_lidar.translation())
                        .norm();
  e.translation_sigma_m = c.extrinsic_translation_sigma_m.maxCoeff();
  e.ate_m = run.ate_m;
  e.searches = run.searches;
  std::printf(
      "scenario %llu (%s), ieskf: rotation error %.3f deg (roll %+.3f, pitch %+.3f, yaw %+.3f; "
      "sigma %.3f deg), translation error %.4f m (sigma %.4f m), correction found %.3f deg; ATE "
      "%.4f m\n",
      static_cast<unsigned long long>(number), summary.c_str(), e.rotation_deg,
      e.rotation_vehicle_deg.x(), e.rotation_vehicle_deg.y(), e.rotation_vehicle_deg.z(),
      e.rotation_sigma_deg, e.translation_m, e.translation_sigma_m,
      c.extrinsic_rotation_correction_rad.norm() / kDeg, e.ate_m);
  return e;
}

TEST_P(OnlineCalibration, IeskfFindsAnExtrinsicRotationLeftOutOfTheConfiguration) {
  const ExtrinsicErrors e = IeskfCalibrate(GetParam(), kRotationError_rad);
  EXPECT_LE(e.rotation_deg, 0.5);
  EXPECT_LE(e.translation_m, 0.05);
  EXPECT_LE(e.ate_m, 0.03);
}

// Scenario 0's guess start is refused and its start comes from a search while the vehicle
// moves off. Estimated in the search's own young map, the extrinsic's roll took up the
// accelerometer bias's jump and the handover carried both into the prior map: 1.06° off
// (docs/results.md). The pipeline now holds the calibration while searching. This is the
// scenario that mechanism was found on, so it guards the mechanism, not a held-out figure.
TEST(OnlineCalibration, IeskfHoldsTheExtrinsicWhileSearchingFromAMovingStart) {
  const ExtrinsicErrors e = IeskfCalibrate(0, kRotationError_rad);
  EXPECT_GE(e.searches, 1u) << "the start no longer comes from a search: the test lost its case";
  EXPECT_LE(e.rotation_deg, 0.5);
  EXPECT_LE(e.translation_m, 0.05);
  EXPECT_LE(e.ate_m, 0.03);
}

TEST(OnlineCalibration, IeskfStaysNearARightConfiguration) {
  const ExtrinsicErrors e = IeskfCalibrate(12, Eigen::Vector3d::Zero());
  EXPECT_LE(e.rotation_deg, 0.5);
  EXPECT_LE(e.translation_m, 0.05);
  EXPECT_LE(e.ate_m, 0.03);
}

INSTANTIATE_TEST_SUITE_P(Unseen, OnlineCalibration, ::testing::Values(2u, 12u),
                         [](const auto& info) { return "Scenario" + std::to_string(info.param); });

}  // namespace
}  // namespace hylo::testing
