#pragma once
// What every front end (the command line, the ROS node) does with a prior map: read it, thin
// it, move it to a local origin near zero and give it to the pipeline with the start guess;
// and write a map of the run back in the map file's own (world) frame. A prior map is a PCD/PLY
// file, or a tiled map directory (tiles/tiled_prior_map.h) for maps larger than memory, whose
// tiles the pipeline streams around the vehicle.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>

#include "hylo/common/point_types.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/io/json.h"
#include "hylo/mapping/prior_map.h"

namespace hylo::run {

/// Reads the PCD/PLY map at `path`, thins it with `options`, and starts `pipeline`'s
/// localization in it from `T_world_imu_guess` (world = the map file's frame; none: the
/// global localizer searches the whole map). Returns the map
/// (its origin_world turns every output back into world coordinates). Throws naming the file
/// when it cannot be read or holds no point. A tiled map directory goes to
/// tiles::LoadTiledPriorMap.
mapping::PriorMap LoadPriorMap(const std::string& path, const mapping::PriorMapOptions& options,
                               const std::optional<Eigen::Isometry3d>& T_world_imu_guess,
                               odometry::OdometryPipeline* pipeline);

/// The prior as one neighbour search, for a run's final metrics: one tree over the whole map,
/// or, for a tiled prior, its tiles read on demand (at most `cache_points` held).
std::unique_ptr<registration::NeighborSearch> PriorSearch(
    const mapping::PriorMap& prior, const odometry::OdometryPipeline& pipeline,
    std::size_t cache_points);

/// Writes `points_map` (map frame, local to `origin_world`) to `path` in world coordinates
/// (PCD, LZF-compressed; PLY or KITTI .bin by extension). Throws naming the file when it
/// cannot be written.
void WriteWorldCloud(const std::string& path, const PointCloud& points_map,
                     const Eigen::Vector3d& origin_world);

}  // namespace hylo::run
