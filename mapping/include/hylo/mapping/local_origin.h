#pragma once
// Large coordinates (UTM: ~10^5..10^6 m) lose centimetres in float. Every cloud that enters
// the core is shifted by an origin kept in double, computed on near zero, and shifted back
// on output.

#include <Eigen/Core>
#include <vector>

#include "hylo/registration/point_types.h"

namespace hylo::mapping {

/// Origin chosen for a cloud: the first finite point rounded to `granularity_m`, so that
/// written coordinates stay round and the shift is easy to read in a file header.
Eigen::Vector3d ChooseOrigin(const std::vector<Eigen::Vector3d>& points_world,
                             double granularity_m = 100.0);

/// points_world - origin, as float. Non-finite points are kept as they are (callers filter).
registration::PointCloud ToLocal(const std::vector<Eigen::Vector3d>& points_world,
                                 const Eigen::Vector3d& origin_world);

/// points_local + origin, in double.
std::vector<Eigen::Vector3d> ToWorld(const registration::PointCloud& points_local,
                                     const Eigen::Vector3d& origin_world);

}  // namespace hylo::mapping
