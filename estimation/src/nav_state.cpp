#include "hylo/estimation/nav_state.h"

namespace hylo::estimation {

using namespace state_index;  // NOLINT: index names only

NavState BoxPlus(const NavState& x, const StateVector& delta) {
  NavState y = x;
  y.R_map_imu = lie::Plus(x.R_map_imu, Eigen::Vector3d(delta.segment<3>(kRotation)));
  y.p_map_imu += delta.segment<3>(kPosition);
  y.v_map_imu += delta.segment<3>(kVelocity);
  y.gyro_bias += delta.segment<3>(kGyroBias);
  y.accel_bias += delta.segment<3>(kAccelBias);
  y.gravity_map += delta.segment<3>(kGravity);
  y.T_imu_lidar.so3() =
      lie::Plus(x.T_imu_lidar.so3(), Eigen::Vector3d(delta.segment<3>(kExtrinsicRotation)));
  y.T_imu_lidar.translation() += delta.segment<3>(kExtrinsicTranslation);
  return y;
}

StateVector BoxMinus(const NavState& y, const NavState& x) {
  StateVector d;
  d.segment<3>(kRotation) = lie::Minus(y.R_map_imu, x.R_map_imu);
  d.segment<3>(kPosition) = y.p_map_imu - x.p_map_imu;
  d.segment<3>(kVelocity) = y.v_map_imu - x.v_map_imu;
  d.segment<3>(kGyroBias) = y.gyro_bias - x.gyro_bias;
  d.segment<3>(kAccelBias) = y.accel_bias - x.accel_bias;
  d.segment<3>(kGravity) = y.gravity_map - x.gravity_map;
  d.segment<3>(kExtrinsicRotation) = lie::Minus(y.T_imu_lidar.so3(), x.T_imu_lidar.so3());
  d.segment<3>(kExtrinsicTranslation) = y.T_imu_lidar.translation() - x.T_imu_lidar.translation();
  return d;
}

PoseCovariance6 PoseBlock(const StateCovariance& P) {
  // Reorder [θ, p] (state) into [p, θ] (pose covariance order).
  PoseCovariance6 out;
  out.block<3, 3>(0, 0) = P.block<3, 3>(kPosition, kPosition);
  out.block<3, 3>(0, 3) = P.block<3, 3>(kPosition, kRotation);
  out.block<3, 3>(3, 0) = P.block<3, 3>(kRotation, kPosition);
  out.block<3, 3>(3, 3) = P.block<3, 3>(kRotation, kRotation);
  return out;
}

}  // namespace hylo::estimation
