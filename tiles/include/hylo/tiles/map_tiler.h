#pragma once
// Cuts a map into a tiled map directory (tiled_map.h) without holding the map in memory:
//  1. the input is read in chunks (cloud_stream.h); each point is shifted to the local origin
//     (the first finite point rounded to origin_granularity_m, as a prior map's), given its
//     tile and appended to that tile's spill file (buffered in memory up to a budget);
//  2. each tile's spill is read back alone, thinned at voxel_m (uniform sampling, the prior
//     map's rule: per voxel the point nearest its centre; a voxel never straddles two tiles,
//     so the tiles together are the whole map thinned at once), written as a PCD, and folded
//     into the overview (lowest point per overview voxel); LAS tiles (tile_format) are written
//     in the world frame, their index bounds those of the quantized points they read back as;
//  3. index.json is written last, and the directory appears under its name only when complete
//     (built beside it and renamed; a previous tiled map of that name is replaced).
// Memory: the chunk, the spill budget and one tile, whatever the map's size. Disk: the map
// once more (spills, float32 x y z) while it runs.

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hylo/tiles/tiled_map.h"

namespace hylo::tiles {

struct TileMapOptions {
  double tile_size_m = 50.0;            ///< edge of a tile, m (> 0; a whole multiple of voxel_m)
  double voxel_m = 0.1;                 ///< tiles thinned by uniform sampling at this voxel, m;
                                        ///< 0 keeps every point
  double overview_voxel_m = 0.5;        ///< overview for the global localizer's raster (lowest
                                        ///< point per voxel), m; 0: no overview
  double origin_granularity_m = 100.0;  ///< local origin = first finite point rounded to this, m
  std::optional<Eigen::Vector3d> origin_world;      ///< or this origin (tiles that must share
                                                    ///< another tiled map's grid), m
  std::size_t chunk_points = std::size_t{1} << 20;  ///< points read at a time (> 0)
  std::size_t spill_buffer_points = std::size_t{1} << 22;  ///< points buffered before they are
                                                           ///< appended to the spill files (> 0)
  TileFormat tile_format = TileFormat::kPcd;  ///< tile files: PCD (local frame, float32) or LAS
                                              ///< (world frame, 0.1 mm; see tiled_map.h)
  bool IsValid(std::string* why) const;
};

struct TileMapSummary {
  std::size_t points_read = 0;     ///< finite input points
  std::size_t non_finite = 0;      ///< input points with a NaN/inf coordinate, dropped
  std::size_t points_written = 0;  ///< after thinning
  std::size_t tiles = 0;
  std::size_t overview_points = 0;
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();
  double split_s = 0.0;  ///< wall time of pass 1 (read, spill), s
  double tiles_s = 0.0;  ///< wall time of pass 2 (thin, write), s
};

/// Gives the next chunk of world positions (finite ones; NaN/inf are counted by the caller) and
/// false once there is none.
using PositionChunks = std::function<bool(std::vector<Eigen::Vector3d>* chunk)>;

/// Tiles the points `next` gives into `out_dir`. `source` is recorded in the index. Throws
/// std::invalid_argument for invalid options or no finite point, std::runtime_error naming
/// the file for I/O failures, or when `out_dir` exists and is not a tiled map (never
/// overwritten). On failure nothing is left under `out_dir`'s name.
TileMapSummary TileMap(const PositionChunks& next, const std::string& source,
                       const std::string& out_dir, const TileMapOptions& options);

/// Tiles the point cloud file `in_path` (PCD/PLY/KITTI .bin/LAS, read in chunks).
TileMapSummary TileMapFile(const std::string& in_path, const std::string& out_dir,
                           const TileMapOptions& options);

}  // namespace hylo::tiles
