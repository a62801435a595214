// IkdTree: k-nearest (with a maximum distance), radius and box search. Subtrees are pruned by
// the squared distance from the query to their box; fully deleted subtrees are skipped.

#include <algorithm>
#include <limits>

#include "hylo/mapping/ikd_tree.h"

namespace hylo::mapping {
namespace {
using registration::Neighbor;
constexpr float kInf = std::numeric_limits<float>::infinity();

float BoxSquaredDistance(const float* lo, const float* hi, const Eigen::Vector3f& q) {
  float d2 = 0.f;
  for (int a = 0; a < 3; ++a) {
    const float below = lo[a] - q[a];
    const float above = q[a] - hi[a];
    const float d = std::max(std::max(below, above), 0.f);
    d2 += d * d;
  }
  return d2;
}

bool ByDistance(const Neighbor& a, const Neighbor& b) {
  return a.squared_distance < b.squared_distance;
}
}  // namespace

// The k nearest so far, nearest first, in the caller's array of k slots (no allocation and
// no vector bookkeeping per candidate: a k = 5 query offers a few dozen candidates).
struct IkdTree::KnnSearch {
  Eigen::Vector3f query;
  int k = 0;
  int found = 0;            // filled slots of `best`
  float worst_d2 = 0.f;     // bound: max distance^2, then the k-th squared distance, m^2
  Neighbor* best = nullptr;

  // Keeps `p` (no farther than worst_d2); ties stay behind the earlier candidates.
  void Offer(const Eigen::Vector3f& p, float d2) {
    int i = found < k ? found++ : k - 1;
    for (; i > 0 && best[i - 1].squared_distance > d2; --i) best[i] = best[i - 1];
    best[i] = Neighbor{p, d2};
    if (found == k) worst_d2 = best[k - 1].squared_distance;
  }
};

void IkdTree::KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                       std::vector<Neighbor>* neighbors) const {
  neighbors->clear();
  const Node& root = nodes_[root_];
  if (k <= 0 || root.invalid == root.size) return;  // children of a labelled root are stale
  neighbors->resize(static_cast<std::size_t>(k));
  KnnSearch search;
  search.query = query;
  search.k = k;
  search.worst_d2 = max_distance * max_distance;
  search.best = neighbors->data();
  KNearestIn(root_, &search);
  neighbors->resize(static_cast<std::size_t>(search.found));
}

void IkdTree::KNearestIn(int node, KnnSearch* search) const {
  const Node& self = nodes_[node];
  const Eigen::Vector3f query = search->query;  // a local: no aliasing with the results
  if (self.IsLeaf()) {
    const Bucket& bucket = buckets_[self.bucket];
    float d2[kBucketCapacity];
    for (int i = 0; i < kBucketCapacity; ++i) {  // all slots (unused are +inf): vectorises
      const float dx = bucket.x[i] - query.x();
      const float dy = bucket.y[i] - query.y();
      const float dz = bucket.z[i] - query.z();
      d2[i] = dx * dx + dy * dy + dz * dz;
    }
    for (uint32_t i = 0; i < bucket.count; ++i) {
      if (d2[i] > search->worst_d2 || ((bucket.deleted >> i) & 1u)) continue;
      search->Offer({bucket.x[i], bucket.y[i], bucket.z[i]}, d2[i]);
    }
    return;
  }
  const Node& left = nodes_[self.child[0]];
  const Node& right = nodes_[self.child[1]];
  const float d_left =
      left.invalid < left.size ? BoxSquaredDistance(left.lo, left.hi, query) : kInf;
  const float d_right =
      right.invalid < right.size ? BoxSquaredDistance(right.lo, right.hi, query) : kInf;
  const bool left_first = d_left <= d_right;
  const int first = self.child[left_first ? 0 : 1];
  const int second = self.child[left_first ? 1 : 0];
  const float d_first = left_first ? d_left : d_right;
  const float d_second = left_first ? d_right : d_left;
  if (d_first <= search->worst_d2) KNearestIn(first, search);
  if (d_second <= search->worst_d2) KNearestIn(second, search);
}

void IkdTree::Radius(const Eigen::Vector3f& query, float radius,
                     std::vector<Neighbor>* neighbors) const {
  neighbors->clear();
  RadiusIn(root_, query, radius * radius, neighbors);
  std::sort(neighbors->begin(), neighbors->end(), ByDistance);
}

void IkdTree::RadiusIn(int node, const Eigen::Vector3f& query, float radius_d2,
                       std::vector<Neighbor>* neighbors) const {
  const Node& self = nodes_[node];
  if (self.invalid == self.size || BoxSquaredDistance(self.lo, self.hi, query) > radius_d2) {
    return;
  }
  if (!self.IsLeaf()) {
    RadiusIn(self.child[0], query, radius_d2, neighbors);
    RadiusIn(self.child[1], query, radius_d2, neighbors);
    return;
  }
  const Bucket& bucket = buckets_[self.bucket];
  for (uint32_t i = 0; i < bucket.count; ++i) {
    if ((bucket.deleted >> i) & 1u) continue;
    const Eigen::Vector3f p(bucket.x[i], bucket.y[i], bucket.z[i]);
    const float d2 = (p - query).squaredNorm();
    if (d2 <= radius_d2) neighbors->push_back({p, d2});
  }
}

void IkdTree::BoxSearch(const Box3f& box, PointCloud* points) const {
  points->clear();
  BoxSearchIn(root_, box, points);
}

void IkdTree::BoxSearchIn(int node, const Box3f& box, PointCloud* points) const {
  const Node& self = nodes_[node];
  if (self.invalid == self.size) return;
  bool inside = true;
  for (int a = 0; a < 3; ++a) {
    if (self.lo[a] > box.max[a] || self.hi[a] < box.min[a]) return;
    inside = inside && self.lo[a] >= box.min[a] && self.hi[a] <= box.max[a];
  }
  if (inside) {
    CollectValid(node, points);
  } else if (!self.IsLeaf()) {
    BoxSearchIn(self.child[0], box, points);
    BoxSearchIn(self.child[1], box, points);
  } else {
    const Bucket& bucket = buckets_[self.bucket];
    for (uint32_t i = 0; i < bucket.count; ++i) {
      if ((bucket.deleted >> i) & 1u) continue;
      const Eigen::Vector3f p(bucket.x[i], bucket.y[i], bucket.z[i]);
      if ((p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all()) {
        points->push_back(p);
      }
    }
  }
}

// BoxSearchIn specialised to one voxel (the on-tree downsampling's question, asked once per
// inserted point): the same pruning and visiting order, but the voxel's points are counted
// and compared in place instead of being copied out and filtered afterwards.
void IkdTree::VoxelSearchIn(int node, VoxelScan* scan) const {
  const Node& self = nodes_[node];
  if (self.invalid == self.size) return;
  const Box3f& box = scan->box;
  for (int a = 0; a < 3; ++a) {
    if (self.lo[a] > box.max[a] || self.hi[a] < box.min[a]) return;
  }
  if (!self.IsLeaf()) {
    VoxelSearchIn(self.child[0], scan);
    VoxelSearchIn(self.child[1], scan);
    return;
  }
  const Bucket& bucket = buckets_[self.bucket];
  for (uint32_t i = 0; i < bucket.count; ++i) {
    if ((bucket.deleted >> i) & 1u) continue;
    const Eigen::Vector3f p(bucket.x[i], bucket.y[i], bucket.z[i]);
    if ((p.array() < box.min.array()).any() || (p.array() > box.max.array()).any()) continue;
    if (VoxelOf(p, scan->voxel_size_m) != scan->key) continue;
    ++scan->count;
    const float d2 = (p - scan->centre).squaredNorm();
    if (d2 < scan->best_d2) {
      scan->best_d2 = d2;
      scan->best = p;
    }
  }
}

}  // namespace hylo::mapping
