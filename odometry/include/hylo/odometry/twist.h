#pragma once
// The body twist that goes with each scan's pose in the odometry stream: with an IMU the
// last gyro sample minus its bias and the velocity estimate; without one, the rate between
// the last two poses. Each with its covariance.

#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/estimation/estimator.h"
#include "hylo/estimation/imu_options.h"
#include "hylo/odometry/scan_result.h"

namespace hylo::odometry {

class TwistEstimator {
 public:
  explicit TwistEstimator(const estimation::ImuOptions& imu) : imu_(imu) {}

  /// Fills result's twist and twist covariance from result->state and result->pose_covariance
  /// (already set), the scan's IMU samples `imu` and the estimator's covariance.
  void Fill(const std::vector<ImuSample>& imu, const estimation::Estimator& estimator, ScanResult* result);

 private:
  estimation::ImuOptions imu_;
  Eigen::Vector3d last_gyro_imu_ = Eigen::Vector3d::Zero();  // last sample, rad/s
  double imu_period_s_ = 0.005;                              // measured sample period, s
  bool have_previous_ = false;                               // for the no-IMU rate
  estimation::NavState previous_state_;
  estimation::PoseCovariance6 previous_pose_covariance_ = estimation::PoseCovariance6::Zero();
};

}  // namespace hylo::odometry
