#pragma once
// A map stored as square tiles (a directory), for maps larger than memory:
//
//   DIR/index.json      what the tiles are (below); written last, so a directory without it
//                       is not a tiled map
//   DIR/tiles/X_Y.pcd   tile (X, Y): binary PCD, float32 x y z in the map's *local* frame
//                       (world = point + origin_world), so UTM maps keep their millimetres
//                       in float32 and every tile loads as it is searched
//   DIR/tiles/X_Y.las   or, when asked for (TileFormat::kLas), LAS 1.4 in the *world* frame, so
//                       survey software shows each tile where it is; LAS keeps 0.1 mm with its
//                       header's offset, and readers here subtract origin_world
//   DIR/overview.pcd    optional: the map thinned to the lowest point per overview voxel
//                       (local frame), what the global localizer's raster is built from
//
// index.json: {"format": "hylo tiled map", "version": 1, "tile_size_m", "voxel_m" (the tiles
// were thinned at this voxel; 0: not thinned), "origin_world": [x, y, z], "source", "points",
// "bounds_local": {"min", "max"}, "overview": {"file", "voxel_m", "points"} or null,
// "tiles": [{"ix", "iy", "file", "points", "min", "max"}]}. Tile (ix, iy) holds the points
// whose voxel (or, unthinned, whose position) has local x in [ix, ix + 1) * tile_size_m, y
// alike; "min"/"max" bound its points exactly (for LAS tiles: the local float32 positions the
// tile reads back as, after its 0.1 mm quantization).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"

namespace hylo::tiles {

/// The file format of a tiled map's tiles (the overview is always PCD).
enum class TileFormat {
  kPcd,  ///< binary PCD, float32 x y z, local frame
  kLas,  ///< LAS 1.4, world frame (0.1 mm grid)
};

struct TiledMapTile {
  int32_t ix = 0;                                       ///< tile column (local x / tile size)
  int32_t iy = 0;                                       ///< tile row (local y / tile size)
  std::string file;                                     ///< relative to the map directory
  std::size_t points = 0;                               ///< points the file holds
  Eigen::Vector3f min_local = Eigen::Vector3f::Zero();  ///< bounds of its points, local, m
  Eigen::Vector3f max_local = Eigen::Vector3f::Zero();
};

struct TiledMapIndex {
  static constexpr int kVersion = 1;
  int version = kVersion;
  double tile_size_m = 50.0;  ///< edge of a tile, m
  double voxel_m = 0.0;       ///< the tiles were thinned at this voxel (0: every point kept), m
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();  ///< world position of local zero, m
  std::string source;                                      ///< what the map was made from
  std::size_t points = 0;                                  ///< points of every tile
  Eigen::Vector3f min_local = Eigen::Vector3f::Zero();     ///< bounds of every point, local, m
  Eigen::Vector3f max_local = Eigen::Vector3f::Zero();
  std::string overview_file;      ///< relative to the map directory; empty: no overview
  double overview_voxel_m = 0.0;  ///< its voxel, m
  std::size_t overview_points = 0;
  std::vector<TiledMapTile> tiles;
};

/// DIR/index.json.
std::string TiledMapIndexPath(const std::string& dir);
/// True when `path` is a directory holding index.json.
bool IsTiledMap(const std::string& path);

/// Reads and checks DIR/index.json. Throws std::runtime_error naming the file and the key for
/// a missing or malformed key, a version newer than this reader, a tile listed twice, tile
/// counts that do not add up to "points", or a tile file outside the directory.
TiledMapIndex ReadTiledMapIndex(const std::string& dir);

/// Writes DIR/index.json atomically (complete or absent).
void WriteTiledMapIndex(const std::string& dir, const TiledMapIndex& index);

/// Checks every tile file against the index without reading the points (headers only): it
/// exists, is a PCD and announces the index's point count. Throws naming the tile file and
/// what does not match.
void CheckTiledMapFiles(const std::string& dir, const TiledMapIndex& index);

/// Reads one tile (local frame; a LAS tile is moved from the world frame by `origin_world`, the
/// index's) and checks it against its entry: the point count and the bounds must be the
/// index's. Throws naming the file for a missing or corrupt tile and for a tile that does not
/// match the index.
PointCloud ReadTiledMapTile(const std::string& dir, const Eigen::Vector3d& origin_world,
                            const TiledMapTile& tile);

/// Reads the overview (local frame); empty when the map has none.
PointCloud ReadTiledMapOverview(const std::string& dir, const TiledMapIndex& index);

/// "tiles/<ix>_<iy>.pcd" (or ".las").
std::string TileFileName(int32_t ix, int32_t iy, TileFormat format = TileFormat::kPcd);

/// True for a tile file stored in the world frame (a LAS tile).
bool IsWorldFrameTile(const std::string& file);

}  // namespace hylo::tiles
