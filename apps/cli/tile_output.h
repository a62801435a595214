#pragma once
// Tiled map output shared by `hylo tile` and the `--tiles DIR` option of `hylo map` and
// `hylo craft` (cmd_tile.cpp).

#include <CLI/CLI.hpp>
#include <string>

#include "hylo/io/json.h"
#include "hylo/tiles/map_tiler.h"

namespace hylo::cli {

/// --tile-size, --<prefix>voxel, --<prefix>overview-voxel into `options` (commands with a
/// --voxel of their own use the prefix "tile-").
void AddTileOptions(CLI::App* cmd, tiles::TileMapOptions* options, const std::string& prefix);

/// Tiles the cloud file `in_path` into `out_dir`; prints and returns the summary (points,
/// tiles, seconds, points per second, peak memory of the process).
io::Json WriteTiles(const std::string& in_path, const std::string& out_dir,
                    const tiles::TileMapOptions& options);

}  // namespace hylo::cli
