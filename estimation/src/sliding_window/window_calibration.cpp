// The smoother's online calibration: its blocks and what they mean for a scan's points.
#include <Eigen/Geometry>
#include <algorithm>

#include "sliding_window_state.h"

namespace hylo::estimation {

std::vector<BlockRef> WindowCalibration::Blocks() {
  std::vector<BlockRef> blocks;
  if (layout.time_offset) blocks.push_back({time_offset_s, 1, false});
  if (layout.extrinsic_rotation) blocks.push_back({extrinsic_rotation, 4, true});
  return blocks;
}

lie::SO3d WindowCalibration::RotationCorrection() const {
  return lie::SO3d(Eigen::Quaterniond(extrinsic_rotation).normalized());
}

lie::SE3d WindowCalibration::T_imu_lidar() const {
  return lie::SE3d(RotationCorrection() * T_imu_lidar_configured.so3(),
                   T_imu_lidar_configured.translation());
}

lie::SE3d WindowCalibration::ObservationPose(const NavState& x,
                                             const Eigen::Vector3d& rate_imu) const {
  const double dt = time_offset_s[0];
  const lie::SE3d T_map_imu_then(x.R_map_imu * lie::SO3d::Exp(rate_imu * dt),
                                 x.p_map_imu + x.v_map_imu * dt);
  // q' = Q (q − t) + t: the rotation correction turns the points about the lidar's origin.
  const lie::SO3d Q = RotationCorrection();
  const Eigen::Vector3d t = T_imu_lidar_configured.translation();
  return T_map_imu_then * lie::SE3d(Q, t - (Q * t));
}

void WindowCalibration::RecentrePriors() {
  time_offset_prior_s = time_offset_s[0];
  std::copy(extrinsic_rotation, extrinsic_rotation + 4, extrinsic_rotation_prior);
}

}  // namespace hylo::estimation
