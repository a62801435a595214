#include "frames.h"

namespace hylo::rosnode {

FramePoses ComputeFramePoses(const Eigen::Isometry3d& T_map_imu,
                             const Eigen::Isometry3d& T_map_odom,
                             const Eigen::Vector3d& origin_world) {
  Eigen::Isometry3d T_world_map = Eigen::Isometry3d::Identity();
  T_world_map.translation() = origin_world;
  FramePoses poses;
  poses.T_world_odom = T_world_map * T_map_odom;
  poses.T_odom_imu = T_map_odom.inverse() * T_map_imu;
  poses.T_world_imu = T_world_map * T_map_imu;
  return poses;
}

std::array<double, 36> PoseCovarianceToRos(const estimation::PoseCovariance6& covariance,
                                           const Eigen::Matrix3d& R_parent_map,
                                           const Eigen::Matrix3d& R_parent_imu) {
  Eigen::Matrix<double, 6, 6> J = Eigen::Matrix<double, 6, 6>::Zero();
  J.topLeftCorner<3, 3>() = R_parent_map;
  J.bottomRightCorner<3, 3>() = R_parent_imu;
  const Eigen::Matrix<double, 6, 6> ros = J * covariance * J.transpose();
  std::array<double, 36> out{};
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) out[6 * r + c] = ros(r, c);
  }
  return out;
}

std::array<double, 36> TwistCovarianceToRos(const Eigen::Matrix<double, 6, 6>& covariance) {
  std::array<double, 36> out{};
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) out[6 * r + c] = covariance(r, c);
  }
  return out;
}

}  // namespace hylo::rosnode
