#pragma once
// Between our SE(3) and Eigen's Isometry3d: registration and I/O speak Eigen transforms, the
// estimators speak lie::SE3d; the frames are the same (T_a_b maps points of b into a).

#include <Eigen/Geometry>

#include "hylo/lie/se3.h"

namespace hylo::lie {

inline Eigen::Isometry3d ToIsometry(const SE3d& T_a_b) {
  Eigen::Isometry3d iso = Eigen::Isometry3d::Identity();
  iso.linear() = T_a_b.so3().Matrix();
  iso.translation() = T_a_b.translation();
  return iso;
}

/// The rotation block is re-orthonormalised (through a quaternion), so a transform built up
/// by many products still gives a proper rotation.
inline SE3d FromIsometry(const Eigen::Isometry3d& T_a_b) {
  return SE3d(SO3d::FromMatrix(T_a_b.linear()), T_a_b.translation());
}

}  // namespace hylo::lie
