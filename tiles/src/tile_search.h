#pragma once
// Internal to hylo::mapping: the exact k-nearest search over tiles shared by TileSet and
// TileCache (tiles.h).

#include <algorithm>
#include <cmath>
#include <vector>

#include "hylo/tiles/tiles.h"

namespace hylo::tiles::internal {

/// Squared distance from `q` to a box (0 inside), m^2.
inline float SquaredDistanceToBox(const Eigen::Vector3f& q, const mapping::Box3f& box) {
  const Eigen::Vector3f below = (box.min - q).cwiseMax(0.f);
  const Eigen::Vector3f above = (q - box.max).cwiseMax(0.f);
  return (below + above).squaredNorm();
}

/// Merges the sorted `more` into the sorted `*best`, keeping the k nearest.
void MergeNearest(const std::vector<registration::Neighbor>& more, int k,
                  std::vector<registration::Neighbor>* best);

/// The k nearest points within max_distance over the tiles of `lookup`: rings of tiles around
/// the query's tile, until no tile outside the rings searched can hold a nearer point.
/// `info(i)` gives tile i's TileInfo, `tree(i)` its tree (loaded on demand by the cache, only
/// for tiles whose bounds are within reach).
template <typename InfoOf, typename TreeOf>
void GridKNearest(const TileGrid& grid, const TileLookup& lookup, const Eigen::Vector3f& q, int k,
                  float max_distance, const InfoOf& info, const TreeOf& tree,
                  std::vector<registration::Neighbor>* neighbors) {
  neighbors->clear();
  if (lookup.empty() || k <= 0 || !q.allFinite()) return;
  // Points may sit a rounding error outside their tile's square (voxel-based assignment).
  constexpr double kSlackM = 0.05;
  thread_local std::vector<registration::Neighbor> found;
  float bound2 = max_distance * max_distance;
  const TileKey c = grid.KeyOf(q);
  const TileKey lo = lookup.min(), hi = lookup.max();
  const double s = grid.tile_size_m();
  for (int r = 0;; ++r) {
    for (int64_t y = int64_t{c.iy} - r; y <= int64_t{c.iy} + r; ++y) {
      if (y < lo.iy || y > hi.iy) continue;
      const bool edge_row = y == int64_t{c.iy} - r || y == int64_t{c.iy} + r;
      const int64_t step = edge_row ? 1 : 2 * std::max(r, 1);
      for (int64_t x = int64_t{c.ix} - r; x <= int64_t{c.ix} + r; x += step) {
        if (x < lo.ix || x > hi.ix) continue;
        const int i = lookup.Find({static_cast<int32_t>(x), static_cast<int32_t>(y)});
        if (i < 0 || SquaredDistanceToBox(q, info(i).bounds_local) > bound2) continue;
        const mapping::IkdTree* t = tree(i);
        if (t == nullptr) continue;
        t->KNearest(q, k, std::sqrt(bound2), &found);
        MergeNearest(found, k, neighbors);
        if (static_cast<int>(neighbors->size()) == k) bound2 = neighbors->back().squared_distance;
      }
    }
    const bool covers = int64_t{c.ix} - r <= lo.ix && int64_t{c.ix} + r >= hi.ix &&
                        int64_t{c.iy} - r <= lo.iy && int64_t{c.iy} + r >= hi.iy;
    if (covers) return;
    const double reach = std::min({q.x() - (c.ix - r) * s, (c.ix + r + 1) * s - q.x(),
                                   q.y() - (c.iy - r) * s, (c.iy + r + 1) * s - q.y()}) -
                         kSlackM;
    if (reach > 0.0 && reach * reach > bound2) return;
  }
}

}  // namespace hylo::tiles::internal
