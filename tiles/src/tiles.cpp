// Tiles of a prior map: the grid, a fixed set of loaded tiles and the on-demand cache
// (tiles.h), with the exact search they share (tile_search.h).
#include "hylo/tiles/tiles.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hylo/common/check.h"
#include "hylo/common/voxel_key.h"
#include "tile_search.h"

namespace hylo::tiles {
namespace internal {

void MergeNearest(const std::vector<registration::Neighbor>& more, int k,
                  std::vector<registration::Neighbor>* best) {
  if (more.empty()) return;
  thread_local std::vector<registration::Neighbor> merged;
  merged.clear();
  std::merge(best->begin(), best->end(), more.begin(), more.end(), std::back_inserter(merged),
             [](const registration::Neighbor& a, const registration::Neighbor& b) {
               return a.squared_distance < b.squared_distance;
             });
  if (static_cast<int>(merged.size()) > k) merged.resize(static_cast<std::size_t>(k));
  best->swap(merged);
}

}  // namespace internal

TileLookup::TileLookup(const std::vector<TileInfo>& tiles) {
  if (tiles.empty()) return;
  min_ = max_ = tiles.front().key;
  for (const TileInfo& t : tiles) {
    min_.ix = std::min(min_.ix, t.key.ix);
    min_.iy = std::min(min_.iy, t.key.iy);
    max_.ix = std::max(max_.ix, t.key.ix);
    max_.iy = std::max(max_.iy, t.key.iy);
  }
  const std::size_t width = static_cast<std::size_t>(int64_t{max_.ix} - min_.ix + 1);
  const std::size_t height = static_cast<std::size_t>(int64_t{max_.iy} - min_.iy + 1);
  index_.assign(width * height, -1);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const TileKey& key = tiles[i].key;
    index_[static_cast<std::size_t>(key.iy - min_.iy) * width +
           static_cast<std::size_t>(key.ix - min_.ix)] = static_cast<int>(i);
  }
}

int TileLookup::Find(const TileKey& key) const {
  if (index_.empty() || key.ix < min_.ix || key.ix > max_.ix || key.iy < min_.iy ||
      key.iy > max_.iy) {
    return -1;
  }
  const std::size_t width = static_cast<std::size_t>(int64_t{max_.ix} - min_.ix + 1);
  return index_[static_cast<std::size_t>(key.iy - min_.iy) * width +
                static_cast<std::size_t>(key.ix - min_.ix)];
}

TileGrid::TileGrid(double tile_size_m) : tile_size_m_(tile_size_m) {
  if (!(tile_size_m > 0.0) || !std::isfinite(tile_size_m)) {
    throw InternalError("TileGrid: tile_size_m = " + std::to_string(tile_size_m) +
                        " must be finite and > 0");
  }
}

TileKey TileGrid::KeyOf(const Eigen::Vector3f& p) const {
  const double inv = 1.0 / tile_size_m_;
  return {static_cast<int32_t>(std::floor(p.x() * inv)),
          static_cast<int32_t>(std::floor(p.y() * inv))};
}

TileKey TileGrid::KeyOf(const Eigen::Vector3f& p, float voxel_m) const {
  const VoxelKey voxel = VoxelOf(p, voxel_m);
  const int64_t n = std::llround(tile_size_m_ / voxel_m);
  auto floor_div = [n](int64_t a) { return a >= 0 ? a / n : -((-a + n - 1) / n); };
  return {static_cast<int32_t>(floor_div(voxel.x())), static_cast<int32_t>(floor_div(voxel.y()))};
}

double TileGrid::SquaredDistanceTo(const TileKey& key, const Eigen::Vector3f& p) const {
  const double x0 = key.ix * tile_size_m_, y0 = key.iy * tile_size_m_;
  const double dx = std::max({x0 - p.x(), 0.0, p.x() - (x0 + tile_size_m_)});
  const double dy = std::max({y0 - p.y(), 0.0, p.y() - (y0 + tile_size_m_)});
  return dx * dx + dy * dy;
}

bool IsWholeMultiple(double tile_size_m, double voxel_m) {
  if (!(voxel_m > 0.0)) return false;
  const double ratio = tile_size_m / voxel_m;
  return ratio >= 1.0 && std::abs(ratio - std::round(ratio)) < 1e-6 * ratio;
}

LoadedTile BuildTile(const TileInfo& info, const PointCloud& points_local) {
  auto tree = std::make_shared<mapping::IkdTree>();
  tree->Build(points_local);
  LoadedTile tile;
  tile.info = info;
  tile.tree = std::move(tree);
  return tile;
}

TileSet::TileSet(double tile_size_m, std::vector<LoadedTile> tiles)
    : grid_(tile_size_m), tiles_(std::move(tiles)) {
  std::sort(tiles_.begin(), tiles_.end(),
            [](const LoadedTile& a, const LoadedTile& b) { return a.info.key < b.info.key; });
  std::vector<TileInfo> infos;
  for (const LoadedTile& t : tiles_) {
    infos.push_back(t.info);
    size_ += t.tree->Size();
  }
  lookup_ = TileLookup(infos);
}

void TileSet::KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                       std::vector<registration::Neighbor>* neighbors) const {
  internal::GridKNearest(
      grid_, lookup_, query, k, max_distance,
      [this](int i) -> const TileInfo& { return tiles_[static_cast<std::size_t>(i)].info; },
      [this](int i) { return tiles_[static_cast<std::size_t>(i)].tree.get(); }, neighbors);
}

const LoadedTile* TileSet::Find(const TileKey& key) const {
  const int i = lookup_.Find(key);
  return i < 0 ? nullptr : &tiles_[static_cast<std::size_t>(i)];
}

std::size_t TileSet::MemoryBytes() const {
  std::size_t bytes = 0;
  for (const LoadedTile& t : tiles_) bytes += t.tree->MemoryBytes();
  return bytes;
}

PointCloud TileSet::Flatten() const {
  PointCloud points;
  for (const LoadedTile& t : tiles_) {
    const PointCloud tile = t.tree->Flatten();
    points.insert(points.end(), tile.begin(), tile.end());
  }
  return points;
}

TileCache::TileCache(std::shared_ptr<const TileSource> source, std::size_t max_points)
    : source_(std::move(source)),
      grid_(source_->tile_size_m()),
      lookup_(source_->tiles()),
      max_points_(max_points) {
  for (const TileInfo& t : source_->tiles()) total_points_ += t.points;
}

const mapping::IkdTree* TileCache::Get(int index) const {
  const TileInfo& info = source_->tiles()[static_cast<std::size_t>(index)];
  for (std::size_t i = 0; i < cached_.size(); ++i) {
    if (cached_[i].info.key != info.key) continue;
    std::rotate(cached_.begin() + static_cast<std::ptrdiff_t>(i),
                cached_.begin() + static_cast<std::ptrdiff_t>(i) + 1, cached_.end());
    return cached_.back().tree.get();
  }
  LoadedTile tile = BuildTile(info, source_->Load(info.key));
  ++loads_;
  cached_points_ += tile.tree->Size();
  cached_.push_back(std::move(tile));
  while (cached_.size() > 1 && cached_points_ > max_points_) {
    cached_points_ -= cached_.front().tree->Size();
    cached_.erase(cached_.begin());
  }
  return cached_.back().tree.get();
}

void TileCache::Clear() {
  cached_.clear();
  cached_.shrink_to_fit();
  cached_points_ = 0;
}

void TileCache::KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                         std::vector<registration::Neighbor>* neighbors) const {
  KNearestPreferring(nullptr, query, k, max_distance, neighbors);
}

void TileCache::KNearestPreferring(const TileSet* preferred, const Eigen::Vector3f& query, int k,
                                   float max_distance,
                                   std::vector<registration::Neighbor>* neighbors) const {
  const std::vector<TileInfo>& tiles = source_->tiles();
  internal::GridKNearest(
      grid_, lookup_, query, k, max_distance,
      [&tiles](int i) -> const TileInfo& { return tiles[static_cast<std::size_t>(i)]; },
      [&](int i) -> const mapping::IkdTree* {
        const LoadedTile* held = preferred == nullptr
                                     ? nullptr
                                     : preferred->Find(tiles[static_cast<std::size_t>(i)].key);
        return held != nullptr ? held->tree.get() : Get(i);
      },
      neighbors);
}

}  // namespace hylo::tiles
