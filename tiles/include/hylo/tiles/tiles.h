#pragma once
// A prior map cut into square tiles of the local frame, for maps larger than memory: only the
// tiles around the vehicle are held, each in its own ikd-tree (tile_streamer.h loads them in a
// background thread). A tree per tile rather than one tree for the window: a tile is built
// entirely off the scan path and joins or leaves the map by a pointer swap, and the points of
// an unloaded tile leave memory with its tree. Queries merge the tiles within reach exactly,
// so the k nearest neighbours are those of one tree over the same points.
//
// Tile (ix, iy) holds points with local x in [ix, ix + 1) * tile_size_m, y alike (a tiler
// thinning at a voxel assigns points by their voxel, so a voxel never straddles two tiles;
// either way every tile carries the exact bounds of its points, which is all the searches use).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/mapping/ikd_tree.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::tiles {

struct TileKey {
  int32_t ix = 0;
  int32_t iy = 0;
  bool operator==(const TileKey& o) const { return ix == o.ix && iy == o.iy; }
  bool operator!=(const TileKey& o) const { return !(*this == o); }
  bool operator<(const TileKey& o) const { return ix != o.ix ? ix < o.ix : iy < o.iy; }
};

/// The square tiles of the local frame.
class TileGrid {
 public:
  /// `tile_size_m` must be finite and > 0 (hylo::InternalError otherwise).
  explicit TileGrid(double tile_size_m);
  /// The tile of a position: floor(x / tile_size), floor(y / tile_size).
  TileKey KeyOf(const Eigen::Vector3f& point_local) const;
  /// The tile of a point for a map thinned at `voxel_m` (> 0, tile_size_m a whole multiple of
  /// it): the tile of its voxel (common/voxel_key.h), so a voxel's points share a tile.
  TileKey KeyOf(const Eigen::Vector3f& point_local, float voxel_m) const;
  /// Horizontal squared distance from `point_local` to the square of `key`, m^2.
  double SquaredDistanceTo(const TileKey& key, const Eigen::Vector3f& point_local) const;
  double tile_size_m() const { return tile_size_m_; }

 private:
  double tile_size_m_;
};

/// True when `tile_size_m` is a whole multiple of `voxel_m` (> 0), within float rounding.
bool IsWholeMultiple(double tile_size_m, double voxel_m);

/// One tile as an index describes it.
struct TileInfo {
  TileKey key;
  mapping::Box3f bounds_local;      ///< bounds of its points (local frame), m
  std::size_t points = 0;  ///< points it holds
};

/// Where a tiled prior's tiles come from: files (run/), memory (tests).
class TileSource {
 public:
  virtual ~TileSource() = default;
  virtual double tile_size_m() const = 0;
  /// Every tile of the map.
  virtual const std::vector<TileInfo>& tiles() const = 0;
  /// The points of tile `key` in the local frame, ready for the tree (thinned as the map
  /// should be). Throws std::runtime_error naming the file and what is wrong (missing,
  /// corrupt, not matching the index). Called from several threads at once.
  virtual PointCloud Load(const TileKey& key) const = 0;
};

/// Tiles of a key range in a dense array, for O(1) lookups (the ranges are small: a window
/// of tiles, or one map's tiles).
class TileLookup {
 public:
  TileLookup() = default;
  explicit TileLookup(const std::vector<TileInfo>& tiles);
  /// Index into the vector given at construction, or -1.
  int Find(const TileKey& key) const;
  bool empty() const { return index_.empty(); }
  TileKey min() const { return min_; }
  TileKey max() const { return max_; }

 private:
  TileKey min_, max_;
  std::vector<int> index_;
};

/// A tile and its tree, immutable once built (shared between the loader and the scan path).
struct LoadedTile {
  TileInfo info;
  std::shared_ptr<const mapping::IkdTree> tree;
};

/// Builds a tile's tree from its points (the loader's and the cache's one way to do it).
LoadedTile BuildTile(const TileInfo& info, const PointCloud& points_local);

/// A fixed set of loaded tiles: what the scan path searches between two swaps.
class TileSet final : public registration::NeighborSearch {
 public:
  TileSet() : TileSet(1.0, {}) {}
  TileSet(double tile_size_m, std::vector<LoadedTile> tiles);

  void KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                std::vector<registration::Neighbor>* neighbors) const override;
  std::size_t Size() const override { return size_; }

  const std::vector<LoadedTile>& tiles() const { return tiles_; }
  /// The tile of `key`, or nullptr when it is not in the set.
  const LoadedTile* Find(const TileKey& key) const;
  /// Heap bytes of the trees.
  std::size_t MemoryBytes() const;
  PointCloud Flatten() const;

 private:
  TileGrid grid_;
  std::vector<LoadedTile> tiles_;  // sorted by key
  TileLookup lookup_;
  std::size_t size_ = 0;
};

/// Every tile of a source as one NeighborSearch, loading tiles synchronously on first use and
/// keeping at most `max_points` points (the least recently used tiles are dropped). For the
/// moments where waiting for a file is acceptable: the start (the global localizer refines
/// hypotheses anywhere in the map), a lost vehicle's relocalization, a run's final metrics.
/// One thread at a time: a query may change the cache.
class TileCache final : public registration::NeighborSearch {
 public:
  TileCache(std::shared_ptr<const TileSource> source, std::size_t max_points);

  void KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                std::vector<registration::Neighbor>* neighbors) const override;
  /// Points of every tile of the source (not only the cached ones).
  std::size_t Size() const override { return total_points_; }
  /// Searches `preferred` first for a tile it holds (no load), the cache otherwise.
  void KNearestPreferring(const TileSet* preferred, const Eigen::Vector3f& query, int k,
                          float max_distance, std::vector<registration::Neighbor>* neighbors) const;
  std::size_t tiles_loaded() const { return loads_; }
  /// Drops every cached tile (the memory returns; later queries read them again).
  void Clear();

 private:
  const mapping::IkdTree* Get(int index) const;  // index into source_->tiles()

  std::shared_ptr<const TileSource> source_;
  TileGrid grid_;
  TileLookup lookup_;
  std::size_t max_points_;
  std::size_t total_points_ = 0;
  mutable std::vector<LoadedTile> cached_;  // most recently used last
  mutable std::size_t cached_points_ = 0;
  mutable std::size_t loads_ = 0;
};

}  // namespace hylo::tiles
