#include "hylo/estimation/initial_uncertainty.h"

#include "hylo/common/option_checks.h"

namespace hylo::estimation {

using namespace state_index;  // NOLINT: index names only

bool InitialUncertainty::IsValid(std::string* why) const {
  return CheckPositive("rotation_sigma_rad", rotation_sigma_rad, why) &&
         CheckPositive("velocity_sigma_mps", velocity_sigma_mps, why) &&
         CheckPositive("gyro_bias_sigma_radps", gyro_bias_sigma_radps, why) &&
         CheckPositive("accel_bias_sigma_mps2", accel_bias_sigma_mps2, why) &&
         CheckPositive("gravity_sigma_mps2", gravity_sigma_mps2, why) &&
         CheckPositive("extrinsic_rotation_sigma_rad", extrinsic_rotation_sigma_rad, why) &&
         CheckPositive("extrinsic_translation_sigma_m", extrinsic_translation_sigma_m, why) &&
         CheckPositive("localized_position_sigma_m", localized_position_sigma_m, why) &&
         CheckPositive("moving_tilt_sigma_rad", moving_tilt_sigma_rad, why) &&
         CheckPositive("moving_velocity_sigma_mps", moving_velocity_sigma_mps, why) &&
         CheckPositive("moving_gyro_bias_sigma_radps", moving_gyro_bias_sigma_radps, why);
}

StateCovariance InitialUncertainty::SlamCovariance() const {
  StateCovariance P = StateCovariance::Zero();
  const auto set = [&P](int index, double sigma) {
    P.block<3, 3>(index, index).diagonal().setConstant(sigma * sigma);
  };
  set(kRotation, rotation_sigma_rad);
  set(kPosition, 1e-4);  // the map frame is defined by the first pose
  set(kVelocity, velocity_sigma_mps);
  set(kGyroBias, gyro_bias_sigma_radps);
  set(kAccelBias, accel_bias_sigma_mps2);
  set(kGravity, gravity_sigma_mps2);
  set(kExtrinsicRotation, extrinsic_rotation_sigma_rad);
  set(kExtrinsicTranslation, extrinsic_translation_sigma_m);
  return P;
}

StateCovariance InitialUncertainty::LocalizedCovariance() const {
  StateCovariance P = SlamCovariance();
  P.block<3, 3>(kPosition, kPosition) =
      localized_position_sigma_m * localized_position_sigma_m * Eigen::Matrix3d::Identity();
  return P;
}

StateCovariance InitialUncertainty::MovingCovariance(const NavState& start) const {
  StateCovariance P = SlamCovariance();
  // Tilt about the map's x and y; yaw stays as tight as a SLAM start's (the map frame's
  // heading is the first pose's). The error state's rotation is in the IMU frame:
  // Σ_imu = Rᵀ Σ_map R.
  const double tilt = moving_tilt_sigma_rad * moving_tilt_sigma_rad;
  const double yaw = rotation_sigma_rad * rotation_sigma_rad;
  const Eigen::Matrix3d R = start.R_map_imu.Matrix();
  P.block<3, 3>(kRotation, kRotation) =
      R.transpose() * Eigen::Vector3d(tilt, tilt, yaw).asDiagonal() * R;
  P.block<3, 3>(kVelocity, kVelocity).diagonal().setConstant(moving_velocity_sigma_mps *
                                                             moving_velocity_sigma_mps);
  P.block<3, 3>(kGyroBias, kGyroBias).diagonal().setConstant(moving_gyro_bias_sigma_radps *
                                                             moving_gyro_bias_sigma_radps);
  return P;
}

}  // namespace hylo::estimation
