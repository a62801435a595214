// IkdTree: insertion (with on-tree voxel downsampling) and deletion of points and boxes with
// lazy labels (the paper's incremental updates). Each update re-checks the criteria on the nodes it
// touched.

#include <algorithm>
#include <cmath>
#include <limits>

#include "hylo/mapping/ikd_tree.h"

namespace hylo::mapping {
namespace {
constexpr float kInfinity = std::numeric_limits<float>::infinity();

bool Disjoint(const float* lo, const float* hi, const Box3f& box) {
  for (int a = 0; a < 3; ++a) {
    if (lo[a] > box.max[a] || hi[a] < box.min[a]) return true;
  }
  return false;
}

bool Contains(const Box3f& box, const float* lo, const float* hi) {
  for (int a = 0; a < 3; ++a) {
    if (lo[a] < box.min[a] || hi[a] > box.max[a]) return false;
  }
  return true;
}

bool Contains(const float* lo, const float* hi, const Eigen::Vector3f& p) {
  return p.x() >= lo[0] && p.x() <= hi[0] && p.y() >= lo[1] && p.y() <= hi[1] && p.z() >= lo[2] &&
         p.z() <= hi[2];
}

bool Contains(const Box3f& box, const Eigen::Vector3f& p) {
  return (p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all();
}
}  // namespace

IkdTree::InsertSummary IkdTree::Insert(const PointCloud& points, float voxel_size_m) {
  InsertSummary summary;
  if (voxel_size_m > 0.f) {
    if (voxel_size_m != cache_voxel_m_) ResetVoxelCache(voxel_size_m);
    GrowVoxelCache();
  }
  // The voxel cache is read at a random set per point, usually a cache miss (the sets span
  // up to 1 MiB): asking for the set a few points ahead overlaps those misses (map insertion
  // ~0.8 -> ~0.7 ms per scan on session A).
  constexpr std::size_t kPrefetchAhead = 8;
  const bool prefetch = voxel_size_m > 0.f && !cache_sets_.empty();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f& p = points[i];
    if (prefetch && i + kPrefetchAhead < points.size()) {
      const Eigen::Vector3f& ahead = points[i + kPrefetchAhead];
      if (ahead.allFinite()) {
        __builtin_prefetch(&cache_sets_[CacheSlotOf(VoxelOf(ahead, voxel_size_m)).set]);
      }
    }
    if (!p.allFinite()) {
      ++summary.num_nonfinite;
    } else if (voxel_size_m > 0.f) {
      const InsertSummary one = InsertDownsampled(p, voxel_size_m);
      summary.num_inserted += one.num_inserted;
      summary.num_replaced += one.num_replaced;
      summary.num_skipped += one.num_skipped;
    } else {
      InsertPoint(p);
      Forget(p);  // its voxel may now hold two points
      CountPoint(p, +1);
      ++summary.num_inserted;
    }
  }
  return summary;
}

// Moves the one map point `old_point` of a voxel to `new_point` in its slot, widening the
// boxes on the way down to it. Equivalent to the paper's delete-then-insert for a voxel, but
// leaves no deleted slot behind (so no rebuild is owed) and costs one descent. Routing by
// split planes may then be off by up to a voxel, which searches never rely on: they prune by
// boxes only.
bool IkdTree::ReplacePoint(int node, const Eigen::Vector3f& old_point,
                           const Eigen::Vector3f& new_point) {
  Node& self = nodes_[node];
  if (self.invalid == self.size || !Contains(self.lo, self.hi, old_point)) return false;
  bool replaced = false;
  if (self.IsLeaf()) {
    Bucket& bucket = buckets_[self.bucket];
    for (uint32_t i = 0; i < bucket.count && !replaced; ++i) {
      if (((bucket.deleted >> i) & 1u) || bucket.x[i] != old_point.x() ||
          bucket.y[i] != old_point.y() || bucket.z[i] != old_point.z()) {
        continue;
      }
      bucket.x[i] = new_point.x();
      bucket.y[i] = new_point.y();
      bucket.z[i] = new_point.z();
      replaced = true;
    }
  } else {
    const int left = self.child[0];
    const int right = self.child[1];
    replaced =
        ReplacePoint(left, old_point, new_point) || ReplacePoint(right, old_point, new_point);
  }
  if (!replaced) return false;
  Node& updated = nodes_[node];
  for (int a = 0; a < 3; ++a) {
    updated.lo[a] = std::min(updated.lo[a], new_point[a]);
    updated.hi[a] = std::max(updated.hi[a], new_point[a]);
  }
  return true;
}

// Walks down to a leaf, pushing lazy labels ahead and counting the point into every node on
// the way; a full leaf first drops its deleted slots and, if still full, is split.
void IkdTree::InsertPoint(const Eigen::Vector3f& point) {
  path_.clear();
  int node = root_;
  while (true) {
    PushDown(node);
    path_.push_back(node);
    Node& self = nodes_[node];
    ++self.size;
    for (int a = 0; a < 3; ++a) {
      self.lo[a] = std::min(self.lo[a], point[a]);
      self.hi[a] = std::max(self.hi[a], point[a]);
    }
    if (self.IsLeaf()) break;
    const float c = point[self.axis];
    int side = c < self.split ? 0 : 1;
    if (c == self.split) {  // ties (duplicates) go to the smaller side to keep balance
      side = nodes_[self.child[0]].size <= nodes_[self.child[1]].size ? 0 : 1;
    }
    node = self.child[side];
  }
  Bucket& bucket = buckets_[nodes_[node].bucket];
  if (bucket.count == kBucketCapacity && bucket.deleted != 0) {
    const int dropped = __builtin_popcount(bucket.deleted);
    uint32_t kept = 0;
    for (uint32_t i = 0; i < bucket.count; ++i) {
      if ((bucket.deleted >> i) & 1u) continue;
      bucket.x[kept] = bucket.x[i];
      bucket.y[kept] = bucket.y[i];
      bucket.z[kept] = bucket.z[i];
      ++kept;
    }
    for (uint32_t i = kept; i < bucket.count; ++i) {
      bucket.x[i] = bucket.y[i] = bucket.z[i] = kInfinity;
    }
    bucket.count = kept;
    bucket.deleted = 0;
    for (int on_path : path_) {
      nodes_[on_path].size -= dropped;
      nodes_[on_path].invalid -= dropped;
    }
  }
  if (bucket.count < kBucketCapacity) {
    bucket.x[bucket.count] = point.x();
    bucket.y[bucket.count] = point.y();
    bucket.z[bucket.count] = point.z();
    ++bucket.count;
  } else {
    SplitLeaf(node, point);
  }
  RebalancePath(path_);
}

// A full leaf of valid points becomes a small balanced subtree holding them and `point`.
void IkdTree::SplitLeaf(int node, const Eigen::Vector3f& point) {
  scratch_points_.clear();
  const int bucket_index = nodes_[node].bucket;
  const Bucket& bucket = buckets_[bucket_index];
  for (uint32_t i = 0; i < bucket.count; ++i) {
    scratch_points_.emplace_back(bucket.x[i], bucket.y[i], bucket.z[i]);
  }
  scratch_points_.push_back(point);
  free_buckets_.push_back(bucket_index);
  nodes_[node].bucket = -1;
  BuildSubtree(node, scratch_points_.begin(), scratch_points_.end());
}

std::size_t IkdTree::Delete(const PointCloud& points) {
  std::size_t deleted = 0;
  for (const Eigen::Vector3f& p : points) {
    if (!p.allFinite()) continue;
    const std::size_t here = DeleteInBox(root_, Box3f{p, p}, nullptr, 0.f);
    if (here > 0) {
      Forget(p);
      CountPoint(p, -static_cast<int>(here));
    }
    deleted += here;
  }
  return deleted;
}

std::size_t IkdTree::DeleteBox(const Box3f& box) {
  if (!box.min.allFinite() && !box.max.allFinite()) return 0;
  if ((box.min.array() > box.max.array()).any()) return 0;
  if (occupancy_.empty()) return DeleteInBox(root_, box, nullptr, 0.f);  // no voxel records
  PointCloud inside;  // the voxel records must know which points go
  BoxSearchIn(root_, box, &inside);
  const std::size_t deleted = DeleteInBox(root_, box, nullptr, 0.f);
  for (const Eigen::Vector3f& p : inside) {
    CountPoint(p, -1);
    Forget(p);
  }
  return deleted;
}

// The paper's box-wise delete: a subtree inside the box only gets a lazy label; a
// subtree partly inside is visited; a node whose counters changed is checked against the
// criteria on the way back up. With `voxel`, only points of that voxel are deleted.
std::size_t IkdTree::DeleteInBox(int node, const Box3f& box, const int64_t* voxel,
                                 float voxel_size_m) {
  Node& self = nodes_[node];
  if (self.invalid == self.size || Disjoint(self.lo, self.hi, box)) return 0;
  if (self.IsLeaf()) {
    Bucket& bucket = buckets_[self.bucket];
    std::size_t deleted = 0;
    for (uint32_t i = 0; i < bucket.count; ++i) {
      if ((bucket.deleted >> i) & 1u) continue;
      const Eigen::Vector3f p(bucket.x[i], bucket.y[i], bucket.z[i]);
      if (!Contains(box, p)) continue;
      if (voxel != nullptr && VoxelOf(p, voxel_size_m) != Eigen::Map<const VoxelKey>(voxel)) {
        continue;
      }
      bucket.deleted |= 1u << i;
      ++deleted;
    }
    self.invalid += static_cast<int32_t>(deleted);
    return deleted;
  }
  if (voxel == nullptr && Contains(box, self.lo, self.hi)) {
    const std::size_t deleted = static_cast<std::size_t>(self.size - self.invalid);
    self.tree_deleted = 1;
    self.invalid = self.size;
    return deleted;
  }
  const int left = self.child[0];
  const int right = self.child[1];
  const std::size_t deleted =
      DeleteInBox(left, box, voxel, voxel_size_m) + DeleteInBox(right, box, voxel, voxel_size_m);
  if (deleted > 0) {
    PullUp(node);
    if (BreaksCriteria(nodes_[node])) Rebuild(node);
  }
  return deleted;
}

}  // namespace hylo::mapping
