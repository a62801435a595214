#pragma once
// The prior map of localization: positions as read from a PCD/PLY file (double, so
// UTM coordinates keep their millimetres; the caller reads them with hylo/io/cloud_io.h),
// shifted by a local origin kept in double so everything downstream computes near zero in
// float, and downsampled to the map resolution. The localizer works in the local frame
// ("map" = world - origin); poses and points go back to the world with the origin.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"

namespace hylo::mapping {

struct PriorMapOptions {
  double resolution_m = 0.1;            ///< uniform-sampling voxel of the map, m (0 = keep all),
                                        ///< >= 0
  double origin_granularity_m = 100.0;  ///< the origin is the first finite point rounded to
                                        ///< this, m (see ChooseOrigin), >= 0
  // --- a tiled map (a directory written by `hylo tile`; its tiles are streamed, tiles.h) ---
  double tile_load_radius_m = 0.0;     ///< tiles whose square comes within this of the vehicle
                                       ///< are held, m; 0 = the scan's reach
                                       ///< (preprocess.max_range_m + planes'
                                       ///< max_neighbor_distance_m), >= 0
  double tile_unload_margin_m = 25.0;  ///< held tiles are dropped beyond the load radius + this
                                       ///< (a vehicle on a tile edge does not reload it), m, >= 0
  double tile_cache_million_points = 4.0;  ///< tiles read on demand (the start, a lost
                                           ///< vehicle, the final metrics) are cached up to
                                           ///< this many points, million, > 0
  bool IsValid(std::string* why) const;
};

struct PriorMap {
  PointCloud points_local;  ///< map points - origin_world, downsampled, m
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();  ///< world position of local zero, m
  std::size_t num_input = 0;       ///< points given
  std::size_t num_non_finite = 0;  ///< NaN/inf points dropped
  std::size_t num_kept = 0;        ///< points after downsampling (= points_local.size())
  std::string tiled_dir;           ///< a tiled map: its directory; points_local is then empty
                                   ///< (the pipeline streams the tiles) and num_kept counts
                                   ///< every tile's points
};

/// Builds the prior map from world positions. Throws std::invalid_argument naming
/// `source_name` (e.g. the file) and the reason when there is no point or no finite point,
/// or when `options` is not valid.
PriorMap BuildPriorMap(const std::vector<Eigen::Vector3d>& points_world,
                       const PriorMapOptions& options,
                       const std::string& source_name = "prior map");

/// A world pose (e.g. a guess typed in UTM) in the local frame of `origin_world`, and back.
Eigen::Isometry3d PoseToLocal(const Eigen::Isometry3d& T_world_body,
                              const Eigen::Vector3d& origin_world);
Eigen::Isometry3d PoseToWorld(const Eigen::Isometry3d& T_local_body,
                              const Eigen::Vector3d& origin_world);

}  // namespace hylo::mapping
