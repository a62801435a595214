#pragma once
// A tiled map as a run's prior: the tiles read from their files (and from DIR/map_added, the
// points earlier hybrid-mode sessions added), streamed into the pipeline around the vehicle;
// what the loader did, for the summary; the points a run added written back as tiles.

#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "hylo/io/json.h"
#include "hylo/mapping/prior_map.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::tiles {

/// Starts `pipeline`'s localization in the tiled map directory `dir` (run/prior_map_io.h's
/// LoadPriorMap for a file): checks the index against every tile's header (a
/// missing tile or a count that disagrees fails here, naming the file), hands the pipeline a
/// TiledPrior streaming the tiles (and over DIR/map_added, the added points of earlier sessions,
/// when present) with the options' tile_* settings, and builds the global localizer's raster
/// from the map's overview. With a guess it returns once the tiles around it are loaded;
/// without one nothing is preloaded (the global start reads tiles on demand). Tiles thinned
/// at a voxel finer than options.resolution_m are thinned again as they load.
mapping::PriorMap LoadTiledPriorMap(const std::string& dir, const mapping::PriorMapOptions& options,
                                    const std::optional<Eigen::Isometry3d>& T_world_imu_guess,
                                    odometry::OdometryPipeline* pipeline);

/// What a tiled prior's loader did (tiles, loads, unloads, most points held, its CPU time),
/// for a run's summary. `pipeline` must localize in a tiled prior.
io::Json TiledPriorJson(const odometry::OdometryPipeline& pipeline);

/// Hybrid mode over a tiled prior: the points the run added (including those its window
/// dropped) and those of the prior's own map_added/ layer, written to `out_dir` as a tiled map
/// in the prior's grid and origin, thinned at `voxel_m` (the run's map voxel). Moving it to
/// <map>/map_added makes the next session start from the grown map. Returns the points written.
std::size_t WriteAddedTiles(const std::string& out_dir, const mapping::PriorMap& prior,
                            const odometry::OdometryPipeline& pipeline, double voxel_m);

/// Every tile of the pipeline's tiled prior as one neighbour search, read on demand (at most
/// `cache_points` held), for a run's final metrics.
std::unique_ptr<registration::NeighborSearch> TiledPriorSearch(
    const odometry::OdometryPipeline& pipeline, std::size_t cache_points);

}  // namespace hylo::tiles
