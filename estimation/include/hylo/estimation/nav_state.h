#pragma once
// The navigation state shared by every back-end, its error-state (tangent) layout and the one
// ⊞/⊟ pair used by the filter, the smoother and the tests.
//
// ERROR-STATE ORDER (24 entries, StateVector / StateCovariance):
//   [ 0.. 2] δθ      rotation of R_map_imu, right perturbation R·Exp(δθ), rad (IMU frame)
//   [ 3.. 5] δp      position of the IMU in the map, p + δp, m (map frame)
//   [ 6.. 8] δv      velocity of the IMU in the map, v + δv, m/s (map frame)
//   [ 9..11] δbg     gyro bias, rad/s
//   [12..14] δba     accelerometer bias, m/s²
//   [15..17] δg      gravity vector in the map, m/s² (3 dof; its norm is kept by a tight prior)
//   [18..20] δθ_il   rotation of T_imu_lidar, right perturbation, rad
//   [21..23] δt_il   translation of T_imu_lidar, m
// POSE COVARIANCE ORDER (6×6, Estimator::PoseCovariance): [δp (map, m); δθ (IMU frame, rad)],
// translation first like the SE3 tangent [ρ; φ] and ROS' [x y z roll pitch yaw].

#include <Eigen/Core>
#include <cstdint>

#include "hylo/lie/se3.h"
#include "hylo/lie/so3.h"

namespace hylo::estimation {

namespace state_index {
constexpr int kRotation = 0;
constexpr int kPosition = 3;
constexpr int kVelocity = 6;
constexpr int kGyroBias = 9;
constexpr int kAccelBias = 12;
constexpr int kGravity = 15;
constexpr int kExtrinsicRotation = 18;
constexpr int kExtrinsicTranslation = 21;
constexpr int kDim = 24;
/// Dimension without the extrinsic (when it is not estimated online).
constexpr int kDimNoExtrinsic = 18;
}  // namespace state_index

using StateVector = Eigen::Matrix<double, state_index::kDim, 1>;
using StateCovariance = Eigen::Matrix<double, state_index::kDim, state_index::kDim>;
using PoseCovariance6 = Eigen::Matrix<double, 6, 6>;

struct NavState {
  int64_t t_ns = 0;                                           ///< time the state refers to
  lie::SO3d R_map_imu;                                        ///< orientation of the IMU
  Eigen::Vector3d p_map_imu = Eigen::Vector3d::Zero();        ///< IMU origin in the map, m
  Eigen::Vector3d v_map_imu = Eigen::Vector3d::Zero();        ///< IMU velocity in the map, m/s
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();        ///< rad/s
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();       ///< m/s²
  Eigen::Vector3d gravity_map = Eigen::Vector3d(0, 0, -9.81); ///< m/s², map -z on flat ground
  lie::SE3d T_imu_lidar;                                      ///< maps lidar points to IMU

  lie::SE3d T_map_imu() const { return lie::SE3d(R_map_imu, p_map_imu); }
  lie::SE3d T_map_lidar() const { return T_map_imu() * T_imu_lidar; }
};

/// x ⊞ δ with the layout above.
NavState BoxPlus(const NavState& x, const StateVector& delta);
/// y ⊟ x, so that BoxPlus(x, BoxMinus(y, x)) == y (rotations within π).
StateVector BoxMinus(const NavState& y, const NavState& x);

/// The pose block of a 24×24 state covariance, in the pose covariance order above.
PoseCovariance6 PoseBlock(const StateCovariance& P);

}  // namespace hylo::estimation
