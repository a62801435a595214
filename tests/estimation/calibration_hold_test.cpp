// Both back-ends through the Estimator interface: a calibration told to hold
// (SetCalibrationHeld, which the pipeline does while a search registers against its own
// scratch map) stays exactly where it is while the vehicle drives, and released, the same
// drive moves it toward the truth. The drive: 3 s along a closed room at 1 m/s, level, an ideal
// IMU, the lidar on the IMU with the configuration 1° off in roll.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "estimation/synthetic_scenes.h"
#include "hylo/estimation/estimator.h"
#include "hylo/estimation/estimator_options.h"
#include "hylo/estimation/imu_options.h"
#include "hylo/estimation/initial_uncertainty.h"
#include "hylo/mapping/ikd_tree.h"

namespace hylo::estimation {
namespace {

constexpr double kGravity = 9.81;
constexpr int64_t kImuPeriodNs = 5'000'000;     // 200 Hz
constexpr int64_t kScanPeriodNs = 100'000'000;  // 10 Hz
constexpr int kScans = 30;
const Eigen::Vector3d kVelocity_mps(0.0, 1.0, 0.0);
const Eigen::Vector3d kStart_m(0.0, -2.0, 1.5);
const Eigen::Vector3d kConfigurationError_rad(M_PI / 180.0, 0.0, 0.0);

// The correction the back-end reports after the drive, rad.
Eigen::Vector3d DriveAndCalibrate(Estimator::Backend backend, bool held) {
  const PointCloud room = hylo::testing::Room();
  mapping::IkdTree map;
  map.Build(room);
  const registration::PlaneMatcher planes(map, registration::PlaneMatcherOptions{});
  EstimatorOptions options;
  options.backend = backend;
  options.ieskf.online_extrinsic = true;
  options.sliding_window.estimate_extrinsic_rotation = true;
  std::unique_ptr<Estimator> estimator = Estimator::Create(options, ImuOptions());
  NavState start;
  start.p_map_imu = kStart_m;
  start.v_map_imu = kVelocity_mps;
  start.gravity_map = Eigen::Vector3d(0.0, 0.0, -kGravity);
  start.T_imu_lidar.so3() = lie::SO3d::Exp(kConfigurationError_rad);
  estimator->Initialize(start, InitialUncertainty().SlamCovariance());
  for (int k = 1; k <= kScans; ++k) {
    const int64_t t_ns = k * kScanPeriodNs;
    for (int64_t t = t_ns - kScanPeriodNs + kImuPeriodNs; t <= t_ns; t += kImuPeriodNs) {
      ImuSample sample;  // level, constant velocity: the specific force is gravity's opposite
      sample.t_ns = t;
      sample.accel_imu = Eigen::Vector3d(0.0, 0.0, kGravity);
      sample.gyro_imu = Eigen::Vector3d::Zero();
      estimator->AddImu(sample);
    }
    // The true lidar is the IMU itself: the room seen from where the vehicle is at t.
    const Eigen::Vector3f at_m = (kStart_m + kVelocity_mps * 1e-9 * double(t_ns)).cast<float>();
    DeskewedScan scan;
    scan.t_ns = t_ns;
    for (std::size_t i = 0; i < room.size(); i += 7) scan.points_lidar.push_back(room[i] - at_m);
    estimator->SetCalibrationHeld(held);
    const UpdateSummary summary = estimator->Update(scan, planes);
    EXPECT_TRUE(summary.applied) << ToString(backend) << " scan " << k << ": " << summary.message;
  }
  estimator->Finish();
  const OnlineCalibration c = estimator->Calibration();
  EXPECT_TRUE(c.extrinsic_rotation_estimated) << ToString(backend);
  return c.extrinsic_rotation_correction_rad;
}

class CalibrationHold : public ::testing::TestWithParam<Estimator::Backend> {};

TEST_P(CalibrationHold, AHeldCalibrationStaysAndAReleasedOneMoves) {
  const Eigen::Vector3d held = DriveAndCalibrate(GetParam(), /*held=*/true);
  const Eigen::Vector3d released = DriveAndCalibrate(GetParam(), /*held=*/false);
  std::printf("[%s] correction after 3 s, held / released: %.6f / %.6f deg (error %.3f deg)\n",
              ToString(GetParam()).c_str(), held.norm() * 180.0 / M_PI,
              released.norm() * 180.0 / M_PI, kConfigurationError_rad.norm() * 180.0 / M_PI);
  EXPECT_EQ(held.norm(), 0.0);
  // Released, the drive moves the extrinsic toward the truth (the identity): the error left
  // is at most half the configured one.
  const lie::SO3d estimated = lie::SO3d::Exp(released) * lie::SO3d::Exp(kConfigurationError_rad);
  EXPECT_LT(estimated.Log().norm(), 0.5 * kConfigurationError_rad.norm());
}

INSTANTIATE_TEST_SUITE_P(BothBackends, CalibrationHold,
                         ::testing::Values(Estimator::Backend::kIeskf,
                                           Estimator::Backend::kSlidingWindow),
                         [](const auto& info) { return ToString(info.param); });

}  // namespace
}  // namespace hylo::estimation
