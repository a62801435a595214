#include "hylo/mapping/local_origin.h"

#include <cmath>

namespace hylo::mapping {

Eigen::Vector3d ChooseOrigin(const std::vector<Eigen::Vector3d>& points_world,
                             double granularity_m) {
  for (const Eigen::Vector3d& p : points_world) {
    if (!p.allFinite()) continue;
    if (granularity_m <= 0.0) return p;
    return (p / granularity_m).array().round().matrix() * granularity_m;
  }
  return Eigen::Vector3d::Zero();
}

registration::PointCloud ToLocal(const std::vector<Eigen::Vector3d>& points_world,
                                 const Eigen::Vector3d& origin_world) {
  registration::PointCloud local;
  local.reserve(points_world.size());
  for (const Eigen::Vector3d& p : points_world) local.push_back((p - origin_world).cast<float>());
  return local;
}

std::vector<Eigen::Vector3d> ToWorld(const registration::PointCloud& points_local,
                                     const Eigen::Vector3d& origin_world) {
  std::vector<Eigen::Vector3d> world;
  world.reserve(points_local.size());
  for (const Eigen::Vector3f& p : points_local) world.push_back(p.cast<double>() + origin_world);
  return world;
}

}  // namespace hylo::mapping
