#include "hylo/odometry/twist.h"

#include <algorithm>

#include "hylo/common/time.h"

namespace hylo::odometry {

void TwistEstimator::Fill(const std::vector<ImuSample>& imu, const estimation::Estimator& estimator,
                          ScanResult* result) {
  const estimation::NavState& x = result->state;
  const Eigen::Matrix3d R_imu_map = x.R_map_imu.Matrix().transpose();
  const estimation::StateCovariance P = estimator.Covariance();
  using estimation::state_index::kGyroBias;
  using estimation::state_index::kVelocity;
  result->linear_velocity_imu = R_imu_map * x.v_map_imu;
  result->twist_covariance.setZero();
  result->twist_covariance.topLeftCorner<3, 3>() =
      R_imu_map * P.block<3, 3>(kVelocity, kVelocity) * R_imu_map.transpose();
  if (imu_.enabled) {
    if (!imu.empty()) last_gyro_imu_ = imu.back().gyro_imu;
    if (imu.size() >= 2) {
      imu_period_s_ =
          NanosToSeconds(imu.back().t_ns - imu.front().t_ns) / static_cast<double>(imu.size() - 1);
    }
    result->angular_velocity_imu = last_gyro_imu_ - x.gyro_bias;
    // One sample's white noise (the continuous density over the sample period) plus the bias.
    const double density = imu_.noise.gyro_noise_density;
    result->twist_covariance.bottomRightCorner<3, 3>() =
        P.block<3, 3>(kGyroBias, kGyroBias) +
        density * density / std::max(imu_period_s_, 1e-4) * Eigen::Matrix3d::Identity();
  } else if (have_previous_ && x.t_ns > previous_state_.t_ns) {
    // No IMU: the mean rate between the last two poses, with the variance of that difference.
    const double dt = NanosToSeconds(x.t_ns - previous_state_.t_ns);
    result->angular_velocity_imu = (previous_state_.R_map_imu.Inverse() * x.R_map_imu).Log() / dt;
    result->twist_covariance.bottomRightCorner<3, 3>() =
        (previous_pose_covariance_.bottomRightCorner<3, 3>() +
         result->pose_covariance.bottomRightCorner<3, 3>()) /
        (dt * dt);
  }
  have_previous_ = true;
  previous_state_ = x;
  previous_pose_covariance_ = result->pose_covariance;
}

}  // namespace hylo::odometry
