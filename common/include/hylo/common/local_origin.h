#pragma once
// Large coordinates (UTM: ~10^5..10^6 m) lose centimetres in float. Every cloud that enters
// the core is shifted by an origin kept in double, computed on near zero, and shifted back
// on output.

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "hylo/common/point_types.h"

namespace hylo {

/// Origin chosen for a cloud: the first finite point rounded to `granularity_m`, so that
/// written coordinates stay round and the shift is easy to read in a file header.
inline Eigen::Vector3d ChooseOrigin(const std::vector<Eigen::Vector3d>& points_world,
                                    double granularity_m = 100.0) {
  for (const Eigen::Vector3d& p : points_world) {
    if (!p.allFinite()) continue;
    if (granularity_m <= 0.0) return p;
    return (p / granularity_m).array().round().matrix() * granularity_m;
  }
  return Eigen::Vector3d::Zero();
}

/// points_world - origin, as float. Non-finite points are kept as they are (callers filter).
inline PointCloud ToLocal(const std::vector<Eigen::Vector3d>& points_world,
                          const Eigen::Vector3d& origin_world) {
  PointCloud local;
  local.reserve(points_world.size());
  for (const Eigen::Vector3d& p : points_world) local.push_back((p - origin_world).cast<float>());
  return local;
}

/// points_local + origin, in double.
inline std::vector<Eigen::Vector3d> ToWorld(const PointCloud& points_local,
                                            const Eigen::Vector3d& origin_world) {
  std::vector<Eigen::Vector3d> world;
  world.reserve(points_local.size());
  for (const Eigen::Vector3f& p : points_local) world.push_back(p.cast<double>() + origin_world);
  return world;
}

}  // namespace hylo
