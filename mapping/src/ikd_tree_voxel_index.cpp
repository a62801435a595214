// IkdTree: the paper's on-tree down-sampling (each voxel keeps the one point nearest its
// centre) and the voxel cache that answers it without a tree search.
//
// Why a cache: a box search per inserted point was the largest cost of `hylo map` (37 % of
// its samples in a profile). Once a place is mapped almost every insert lands in a voxel holding
// exactly one point, and then the decision needs only that point. A complete index of every
// occupied voxel paid that back in time but cost ~32 B per map point (81.6 B/point in all,
// over the 64 B/point memory target). A scan revisits mostly the voxels of recent scans, so a
// bounded cache of recently used voxels answers most inserts: 4-way set-associative, one 64-byte
// line per set, least recently used evicted, about one voxel per two map points (<= 10 B/point) and
// at most Options::voxel_cache_max in all (1 MiB by default: 2 B/point at 500k points). A
// miss is decided by one byte per two or more map points, valid points counted per hash of
// their voxel: a zero proves a new voxel empty; otherwise (an evicted voxel, one with several
// points, or a hash shared with an occupied voxel) a search of the voxel in the tree decides,
// which is always right.
//
// Exactness: a cached voxel holds exactly one valid map point, the cached one. Every update
// that could break this forgets the voxel: a plain insert or a point delete forgets the
// point's voxel, and a box delete lists its points first and does the same for each. Every
// point added or deleted is counted. Rebuilds move no point in or out of the map, so they
// leave both alone.
//
// Measured (hylo_ikd_tree_benchmark, workload 3 at ~500k points): 78 % of inserts answered by
// the cache, 13 % proven empty, 9 % searched. Where a scan sees the whole map each time (a
// small site, simulator session A) a cache of half the map thrashes and about half of the
// inserts are searched: the price of staying within the memory target.

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <sstream>

#include "hylo/mapping/ikd_tree.h"

namespace hylo::mapping {
namespace {

// Box slightly larger than voxel `key`, so that no point whose VoxelOf is `key` falls outside
// it through rounding; members are then filtered by VoxelOf itself.
Box3f VoxelSearchBox(const Eigen::Matrix<int64_t, 3, 1>& key, float voxel_size_m) {
  const Eigen::Vector3f centre = VoxelCentre(key, voxel_size_m);
  const float margin = 0.01f * voxel_size_m + 4e-7f * centre.cwiseAbs().maxCoeff();
  const Eigen::Vector3f half = Eigen::Vector3f::Constant(0.5f * voxel_size_m + margin);
  return {centre - half, centre + half};
}

constexpr std::size_t kMinCacheVoxels = 256;
constexpr std::size_t kMapPointsPerCachedVoxel = 2;

}  // namespace

IkdTree::InsertSummary IkdTree::InsertDownsampled(const Eigen::Vector3f& point,
                                                  float voxel_size_m) {
  InsertSummary summary;
  const VoxelKey key = VoxelOf(point, voxel_size_m);
  const bool cached = !cache_sets_.empty();
  const CacheSlot slot = cached ? CacheSlotOf(key) : CacheSlot{0, 0};
  const int way = cached ? FindWay(slot, key) : -1;
  if (way >= 0) {  // the usual case: compare with the voxel's one point
    const CacheSet& set = cache_sets_[slot.set];
    const Eigen::Vector3f old_point(set.x[way], set.y[way], set.z[way]);
    const Eigen::Vector3f centre = VoxelCentre(key, voxel_size_m);
    if (!((point - centre).squaredNorm() < (old_point - centre).squaredNorm())) {
      ++stats_.num_voxel_cache_hits;
      Remember(slot, key, old_point);  // most recently used first
      summary.num_skipped = 1;
      return summary;
    }
    if (ReplacePoint(root_, old_point, point)) {
      ++stats_.num_voxel_cache_hits;
      Remember(slot, key, point);
      summary.num_inserted = 1;
      summary.num_replaced = 1;
      return summary;
    }
  }
  if (!occupancy_.empty() && occupancy_[OccupancyIndex(key)] == 0) {  // surely empty
    ++stats_.num_voxels_proven_empty;
    InsertPoint(point);
    CountInVoxel(key, +1);
    if (cached) Remember(slot, key, point);
    summary.num_inserted = 1;
    return summary;
  }
  ++stats_.num_voxel_searches;
  Eigen::Vector3f kept;
  summary = InsertBySearch(point, voxel_size_m, &kept);
  if (cached) Remember(slot, key, kept);  // the search leaves the voxel one point
  return summary;
}

// The down-sampling decided by a search of the voxel's map points; `kept` receives the
// voxel's one point afterwards.
IkdTree::InsertSummary IkdTree::InsertBySearch(const Eigen::Vector3f& point, float voxel_size_m,
                                               Eigen::Vector3f* kept) {
  InsertSummary summary;
  VoxelScan scan;
  scan.key = VoxelOf(point, voxel_size_m);
  scan.centre = VoxelCentre(scan.key, voxel_size_m);
  scan.box = VoxelSearchBox(scan.key, voxel_size_m);
  scan.voxel_size_m = voxel_size_m;
  scan.best_d2 = std::numeric_limits<float>::infinity();
  scan.best = point;
  VoxelSearchIn(root_, &scan);
  const bool new_is_nearer = (point - scan.centre).squaredNorm() < scan.best_d2;
  *kept = new_is_nearer ? point : scan.best;
  if (scan.count == 0) {
    summary.num_inserted = 1;
  } else if (new_is_nearer) {
    summary.num_inserted = 1;
    summary.num_replaced = scan.count;
  } else {
    summary.num_skipped = 1;
    if (scan.count == 1) return summary;  // no change
  }
  if (scan.count == 1 && ReplacePoint(root_, scan.best, point)) return summary;
  if (scan.count > 0) {
    const std::size_t deleted = DeleteInBox(root_, scan.box, scan.key.data(), voxel_size_m);
    CountInVoxel(scan.key, -static_cast<int>(deleted));
  }
  InsertPoint(*kept);
  CountInVoxel(scan.key, +1);
  return summary;
}

// Empties the cache and keeps it for voxel edge `voxel_size_m` (0: no cache, memory freed).
void IkdTree::ResetVoxelCache(float voxel_size_m) {
  std::vector<CacheSet>().swap(cache_sets_);
  std::vector<uint8_t>().swap(occupancy_);
  cache_voxel_m_ = voxel_size_m;
  GrowVoxelCache();
}

// Sizes the occupancy counts to the smallest power of two >= 2 per valid point and counts
// every valid point again (doubling keeps this O(1) amortised per inserted point).
void IkdTree::RecountOccupancy() {
  std::size_t size = 1024;
  while (size < 2 * Size()) size *= 2;
  occupancy_.assign(size, 0);
  PointCloud points;
  CollectValid(root_, &points);
  for (const Eigen::Vector3f& p : points) CountPoint(p, +1);
}

std::size_t IkdTree::OccupancyIndex(const VoxelKey& key) const {
  const uint64_t h = (static_cast<uint64_t>(key.x()) * 73856093u) ^
                     (static_cast<uint64_t>(key.y()) * 19349663u) ^
                     (static_cast<uint64_t>(key.z()) * 83492791u);
  return static_cast<std::size_t>((h * 0xC2B2AE3D27D4EB4Full) >> 32) & (occupancy_.size() - 1);
}

void IkdTree::CountInVoxel(const VoxelKey& key, int delta) {
  if (occupancy_.empty() || delta == 0) return;
  uint8_t& count = occupancy_[OccupancyIndex(key)];
  if (count == 255) return;  // saturated: stays "maybe occupied"
  count = static_cast<uint8_t>(std::clamp(static_cast<int>(count) + delta, 0, 255));
}

void IkdTree::CountPoint(const Eigen::Vector3f& point, int delta) {
  if (!occupancy_.empty()) CountInVoxel(VoxelOf(point, cache_voxel_m_), delta);
}

// Sizes the cache to one voxel per kMapPointsPerCachedVoxel valid points (at least
// kMinCacheVoxels, at most Options::voxel_cache_max), growing by a quarter or more at a time so
// that it never holds more than 1.25 voxels per kMapPointsPerCachedVoxel points; keeps what
// it holds.
void IkdTree::GrowVoxelCache() {
  if (cache_voxel_m_ <= 0.f) return;
  if (occupancy_.size() < 2 * Size() || occupancy_.empty()) RecountOccupancy();
  const auto max_voxels = static_cast<std::size_t>(options_.voxel_cache_max);
  if (max_voxels == 0) return;
  const std::size_t have = cache_sets_.size() * kCacheWays;
  const std::size_t want =
      std::min(max_voxels, std::max(kMinCacheVoxels, Size() / kMapPointsPerCachedVoxel));
  if (want <= have || (have > 0 && 4 * want < 5 * have && want < max_voxels)) return;
  const std::size_t voxels = std::min(max_voxels, std::max(want, have + have / 4));
  std::vector<CacheSet> old((voxels + kCacheWays - 1) / kCacheWays, CacheSet{{}, {}, {}, {}});
  old.swap(cache_sets_);
  for (const CacheSet& set : old) {
    for (int w = kCacheWays - 1; w >= 0; --w) {  // oldest first
      if (set.tag[w] == 0) continue;
      const Eigen::Vector3f p(set.x[w], set.y[w], set.z[w]);
      const VoxelKey key = VoxelOf(p, cache_voxel_m_);
      Remember(CacheSlotOf(key), key, p);
    }
  }
}

IkdTree::CacheSlot IkdTree::CacheSlotOf(const VoxelKey& key) const {
  // Spatial-hash primes (Teschner et al. 2003), then a Fibonacci mix: the set comes from
  // the high half, the tag from bits the set does not use.
  const uint64_t h = (static_cast<uint64_t>(key.x()) * 73856093u) ^
                     (static_cast<uint64_t>(key.y()) * 19349663u) ^
                     (static_cast<uint64_t>(key.z()) * 83492791u);
  const uint64_t mixed = h * 0x9E3779B97F4A7C15ull;
  // Multiply-shift maps the high 32 bits onto [0, sets) for any count of sets.
  const auto set = static_cast<std::size_t>(((mixed >> 32) * cache_sets_.size()) >> 32);
  return {set, static_cast<uint32_t>(mixed >> 8) | 1u};
}

// A tag match is only a hint; the stored point's own voxel decides.
int IkdTree::FindWay(CacheSlot slot, const VoxelKey& key) const {
  const CacheSet& set = cache_sets_[slot.set];
  for (int w = 0; w < kCacheWays && set.tag[w] != 0; ++w) {
    if (set.tag[w] == slot.tag &&
        VoxelOf({set.x[w], set.y[w], set.z[w]}, cache_voxel_m_) == key) {
      return w;
    }
  }
  return -1;
}

// Puts voxel `key` with its one point first in its set, dropping the least recently used
// voxel when the set is full.
void IkdTree::Remember(CacheSlot slot, const VoxelKey& key, const Eigen::Vector3f& point) {
  CacheSet& set = cache_sets_[slot.set];
  int last = FindWay(slot, key);
  if (last < 0) {
    last = kCacheWays - 1;
    while (last > 0 && set.tag[last - 1] == 0) --last;  // the first unused way, or the last
  }
  for (int w = last; w > 0; --w) {
    set.x[w] = set.x[w - 1];
    set.y[w] = set.y[w - 1];
    set.z[w] = set.z[w - 1];
    set.tag[w] = set.tag[w - 1];
  }
  set.x[0] = point.x();
  set.y[0] = point.y();
  set.z[0] = point.z();
  set.tag[0] = slot.tag;
}

void IkdTree::Forget(const Eigen::Vector3f& point) {
  if (cache_sets_.empty()) return;
  const VoxelKey key = VoxelOf(point, cache_voxel_m_);
  const CacheSlot slot = CacheSlotOf(key);
  const int way = FindWay(slot, key);
  if (way < 0) return;
  CacheSet& set = cache_sets_[slot.set];
  for (int w = way; w + 1 < kCacheWays; ++w) {
    set.x[w] = set.x[w + 1];
    set.y[w] = set.y[w + 1];
    set.z[w] = set.z[w + 1];
    set.tag[w] = set.tag[w + 1];
  }
  set.tag[kCacheWays - 1] = 0;
}

// The cache against a count of the valid points (for CheckInvariants).
bool IkdTree::CheckVoxelIndex(std::string* why) const {
  if (cache_sets_.empty() && occupancy_.empty()) return true;
  PointCloud points;
  if (root_ >= 0) CollectValid(root_, &points);
  std::map<std::array<int64_t, 3>, std::pair<int32_t, Eigen::Vector3f>> truth;
  for (const Eigen::Vector3f& p : points) {
    const VoxelKey k = VoxelOf(p, cache_voxel_m_);
    auto [it, added] = truth.try_emplace({k.x(), k.y(), k.z()}, 1, p);
    if (!added) ++it->second.first;
  }
  std::ostringstream os;
  for (const CacheSet& set : cache_sets_) {
    for (int w = 0; w < kCacheWays && set.tag[w] != 0 && os.str().empty(); ++w) {
      const Eigen::Vector3f p(set.x[w], set.y[w], set.z[w]);
      const VoxelKey key = VoxelOf(p, cache_voxel_m_);
      const auto it = truth.find({key.x(), key.y(), key.z()});
      if (it == truth.end() || it->second.first != 1) {
        os << "voxel cache holds a voxel with " << (it == truth.end() ? 0 : it->second.first)
           << " points, not 1";
      } else if (it->second.second != p) {
        os << "voxel cache holds a point that is not its voxel's one point";
      } else if (const CacheSlot slot = CacheSlotOf(key);
                 &cache_sets_[slot.set] != &set || set.tag[w] != slot.tag ||
                 FindWay(slot, key) != w) {
        os << "voxel cache holds a voxel in the wrong set, with a wrong tag or twice";
      }
    }
    for (int w = 1; w < kCacheWays && os.str().empty(); ++w) {
      if (set.tag[w - 1] == 0 && set.tag[w] != 0) os << "voxel cache set has a gap";
    }
    if (!os.str().empty()) break;
  }
  if (os.str().empty() && !occupancy_.empty()) {
    std::vector<int> counts(occupancy_.size(), 0);
    for (const Eigen::Vector3f& p : points) ++counts[OccupancyIndex(VoxelOf(p, cache_voxel_m_))];
    for (std::size_t i = 0; i < counts.size() && os.str().empty(); ++i) {
      // A saturated count may stay high after deletes: allowed, it only costs a search.
      if (occupancy_[i] != 255 && occupancy_[i] != counts[i]) {
        os << "occupancy count " << int{occupancy_[i]} << " != " << counts[i] << " valid points";
      }
    }
  }
  if (os.str().empty()) return true;
  if (why != nullptr) *why = os.str();
  return false;
}

}  // namespace hylo::mapping
