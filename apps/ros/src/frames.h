#pragma once
// REP-105 frames of the node, in plain Eigen (no ROS type), so they are unit-tested without a
// master. "world" is the frame of the prior map's file (the published `map` frame): the
// pipeline works in a local frame (world - origin, mapping/prior_map.h) and everything that
// leaves the node gets the origin added back. Without a prior map the origin is zero.

#include <Eigen/Geometry>
#include <array>
#include <string>

#include "hylo/estimation/nav_state.h"

namespace hylo::rosnode {

/// The three transforms of one scan result, in the published frames.
struct FramePoses {
  Eigen::Isometry3d T_world_odom = Eigen::Isometry3d::Identity();  ///< map → odom (TF)
  Eigen::Isometry3d T_odom_imu = Eigen::Isometry3d::Identity();    ///< odom → base (TF)
  Eigen::Isometry3d T_world_imu = Eigen::Isometry3d::Identity();   ///< map → base (odometry)
};

/// From the pipeline's T_map_imu and T_map_odom (both in the local map frame) and the local
/// origin: T_world_odom = T_world_map · T_map_odom and T_odom_imu = T_map_odom⁻¹ · T_map_imu,
/// so that T_world_odom · T_odom_imu = T_world_imu exactly (REP-105: odom stays continuous,
/// relocalization jumps live in map → odom).
FramePoses ComputeFramePoses(const Eigen::Isometry3d& T_map_imu,
                             const Eigen::Isometry3d& T_map_odom,
                             const Eigen::Vector3d& origin_world);

/// ROS' row-major 6×6 pose covariance, order [x y z rotX rotY rotZ], with both blocks about the
/// axes of the pose's parent frame ("fixed-axis", geometry_msgs/PoseWithCovariance), from
/// ours, [δp (map frame, m); δθ (IMU frame, right perturbation, rad)] (nav_state.h).
/// R_parent_map rotates the map frame into the parent frame (identity for the world frame:
/// the origin is a pure translation); R_parent_imu is the body's orientation in the parent.
/// A right perturbation δθ_imu is the left perturbation R_parent_imu·δθ_imu, so
/// Σ_ros = J Σ Jᵀ with J = diag(R_parent_map, R_parent_imu); cross blocks follow.
std::array<double, 36> PoseCovarianceToRos(const estimation::PoseCovariance6& covariance,
                                           const Eigen::Matrix3d& R_parent_map,
                                           const Eigen::Matrix3d& R_parent_imu);

/// ROS' twist covariance, order [vx vy vz ωx ωy ωz] in the child frame (the body), from ours,
/// [v (IMU frame); ω (IMU frame)]: the same order and frame, copied row-major.
std::array<double, 36> TwistCovarianceToRos(const Eigen::Matrix<double, 6, 6>& covariance);

}  // namespace hylo::rosnode
