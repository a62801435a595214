#pragma once
// One cloud moved into another frame: the map from the lidar, the search frame from the IMU.

#include <Eigen/Core>

#include "hylo/common/point_types.h"

namespace hylo {

/// Every point of `points_from` in the frame `T_to_from` maps into, in order. `Transform` is
/// anything that maps an Eigen::Vector3d (Eigen::Isometry3d, lie::SE3d); the product is taken
/// in double so a large translation costs no float resolution before the result is rounded.
template <class Transform>
PointCloud Transformed(const Transform& T_to_from, const PointCloud& points_from) {
  PointCloud points_to;
  points_to.reserve(points_from.size());
  for (const Eigen::Vector3f& p : points_from) {
    points_to.push_back((T_to_from * p.cast<double>()).template cast<float>());
  }
  return points_to;
}

}  // namespace hylo
