// Prior map loading for localization (see prior_map.h).
#include "hylo/mapping/prior_map.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "hylo/common/local_origin.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::mapping {

bool PriorMapOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(resolution_m >= 0.0) || !std::isfinite(resolution_m)) {
    os << "resolution_m = " << resolution_m << ": must be finite and >= 0";
  } else if (!(origin_granularity_m >= 0.0) || !std::isfinite(origin_granularity_m)) {
    os << "origin_granularity_m = " << origin_granularity_m << ": must be finite and >= 0";
  } else if (!(tile_load_radius_m >= 0.0) || !std::isfinite(tile_load_radius_m)) {
    os << "tile_load_radius_m = " << tile_load_radius_m << ": must be finite and >= 0 (0: auto)";
  } else if (!(tile_unload_margin_m >= 0.0) || !std::isfinite(tile_unload_margin_m)) {
    os << "tile_unload_margin_m = " << tile_unload_margin_m << ": must be finite and >= 0";
  } else if (!(tile_cache_million_points > 0.0) || !std::isfinite(tile_cache_million_points)) {
    os << "tile_cache_million_points = " << tile_cache_million_points << ": must be finite and > 0";
  }
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

PriorMap BuildPriorMap(const std::vector<Eigen::Vector3d>& points_world,
                       const PriorMapOptions& options, const std::string& source_name) {
  std::string why;
  if (!options.IsValid(&why)) {
    throw std::invalid_argument(source_name + ": PriorMapOptions: " + why);
  }
  PriorMap map;
  map.num_input = points_world.size();
  if (points_world.empty()) throw std::invalid_argument(source_name + ": the map has no point");
  std::vector<Eigen::Vector3d> finite;
  finite.reserve(points_world.size());
  for (const Eigen::Vector3d& p : points_world) {
    if (p.allFinite()) finite.push_back(p);
  }
  map.num_non_finite = points_world.size() - finite.size();
  if (finite.empty()) {
    throw std::invalid_argument(source_name + ": all " + std::to_string(points_world.size()) +
                                " map points are NaN or infinite");
  }
  // Shift first (in double), then downsample in float near zero: voxel indices of UTM-sized
  // float coordinates would already be off by the float spacing (~6 cm at 5e5 m).
  map.origin_world = ChooseOrigin(finite, options.origin_granularity_m);
  map.points_local = registration::UniformSample(ToLocal(finite, map.origin_world),
                                                 static_cast<float>(options.resolution_m));
  map.num_kept = map.points_local.size();
  return map;
}

Eigen::Isometry3d PoseToLocal(const Eigen::Isometry3d& T_world_body,
                              const Eigen::Vector3d& origin_world) {
  Eigen::Isometry3d T = T_world_body;
  T.translation() -= origin_world;
  return T;
}

Eigen::Isometry3d PoseToWorld(const Eigen::Isometry3d& T_local_body,
                              const Eigen::Vector3d& origin_world) {
  Eigen::Isometry3d T = T_local_body;
  T.translation() += origin_world;
  return T;
}

}  // namespace hylo::mapping
