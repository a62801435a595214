// IkdTree: options, node and bucket storage, balanced (re)construction, label push-down and
// flattening. The tree is two arrays (nodes, leaf buckets) addressed by index, with free lists,
// so a partial rebuild reuses the slots of the subtree it replaces.

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "hylo/common/check.h"
#include "hylo/mapping/ikd_tree.h"

namespace hylo::mapping {
namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();

// Leaves a median split of n points into leaves of at most leaf_size produces.
std::size_t CountLeaves(std::size_t n, std::size_t leaf_size) {
  if (n <= leaf_size) return 1;
  return CountLeaves(n / 2, leaf_size) + CountLeaves(n - n / 2, leaf_size);
}

// Grows a full array by 1/4 instead of doubling: the arrays are most of the map's memory,
// and a doubled array would leave up to half of it unused (the target is <= 64 B/point).
template <typename T>
void GrowGently(std::vector<T>* array) {
  if (array->size() < array->capacity()) return;
  array->reserve(array->capacity() + std::max<std::size_t>(array->capacity() / 4, 1024));
}
}  // namespace

bool IkdTree::Options::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(alpha_balance > 0.5f && alpha_balance < 1.f)) {
    os << "alpha_balance = " << alpha_balance << " must be in (0.5, 1)";
  } else if (!(alpha_delete > 0.f && alpha_delete < 1.f)) {
    os << "alpha_delete = " << alpha_delete << " must be in (0, 1)";
  } else if (leaf_size < 1 || leaf_size > kBucketCapacity) {
    os << "leaf_size = " << leaf_size << " must be in [1, " << kBucketCapacity << "]";
  } else if (min_checked_size < 2) {
    os << "min_checked_size = " << min_checked_size << " must be >= 2";
  } else if (voxel_cache_max != 0 && voxel_cache_max < kCacheWays) {
    os << "voxel_cache_max = " << voxel_cache_max << " must be 0 or >= " << kCacheWays;
  }
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

IkdTree::IkdTree() : IkdTree(Options()) {}

IkdTree::IkdTree(Options options) : options_(options) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("IkdTree::Options: " + why);
  Build({});
}

void IkdTree::Build(const PointCloud& points) {
  nodes_.clear();
  buckets_.clear();
  free_nodes_.clear();
  free_buckets_.clear();
  scratch_points_.clear();
  for (const Eigen::Vector3f& p : points) {
    if (p.allFinite()) scratch_points_.push_back(p);
  }
  const std::size_t leaves = CountLeaves(scratch_points_.size(), options_.leaf_size);
  nodes_.reserve(2 * leaves - 1);
  buckets_.reserve(leaves);
  root_ = NewNode();
  BuildSubtree(root_, scratch_points_.begin(), scratch_points_.end());
  scratch_points_.clear();
  scratch_points_.shrink_to_fit();
  ResetVoxelCache(0.f);  // refilled by the next down-sampling inserts
}

int IkdTree::NewNode() {
  Node blank{};
  blank.child[0] = blank.child[1] = -1;
  blank.bucket = -1;
  if (!free_nodes_.empty()) {
    const int index = free_nodes_.back();
    free_nodes_.pop_back();
    nodes_[index] = blank;
    return index;
  }
  GrowGently(&nodes_);
  nodes_.push_back(blank);
  return static_cast<int>(nodes_.size()) - 1;
}

int IkdTree::NewBucket() {
  Bucket empty;
  std::fill(std::begin(empty.x), std::end(empty.x), kInf);
  std::fill(std::begin(empty.y), std::end(empty.y), kInf);
  std::fill(std::begin(empty.z), std::end(empty.z), kInf);
  empty.count = 0;
  empty.deleted = 0;
  if (!free_buckets_.empty()) {
    const int index = free_buckets_.back();
    free_buckets_.pop_back();
    buckets_[index] = empty;
    return index;
  }
  GrowGently(&buckets_);
  buckets_.push_back(empty);
  return static_cast<int>(buckets_.size()) - 1;
}

void IkdTree::FreeSubtree(int node) {
  const Node copy = nodes_[node];
  if (copy.IsLeaf()) {
    free_buckets_.push_back(copy.bucket);
  } else {
    FreeSubtree(copy.child[0]);
    FreeSubtree(copy.child[1]);
  }
  free_nodes_.push_back(node);
}

// Median split on the axis of largest extent (a balanced tree: the paper's Build).
void IkdTree::BuildSubtree(int node, PointCloud::iterator begin, PointCloud::iterator end) {
  const std::ptrdiff_t n = end - begin;
  if (n <= options_.leaf_size) {
    MakeLeaf(node, begin, end);
    return;
  }
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(kInf);
  Eigen::Vector3f hi = Eigen::Vector3f::Constant(-kInf);
  for (auto it = begin; it != end; ++it) {
    lo = lo.cwiseMin(*it);
    hi = hi.cwiseMax(*it);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const auto mid = begin + n / 2;
  std::nth_element(begin, mid, end, [axis](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
    return a[axis] < b[axis];
  });
  const int left = NewNode();
  const int right = NewNode();
  Node& self = nodes_[node];
  self.axis = static_cast<uint8_t>(axis);
  self.split = (*mid)[axis];
  self.child[0] = left;
  self.child[1] = right;
  self.bucket = -1;
  BuildSubtree(left, begin, mid);
  BuildSubtree(right, mid, end);
  PullUp(node);
}

void IkdTree::MakeLeaf(int node, PointCloud::const_iterator begin, PointCloud::const_iterator end) {
  HYLO_CHECK(end - begin <= kBucketCapacity, "a leaf holds at most kBucketCapacity points");
  const int bucket_index = NewBucket();
  Bucket& bucket = buckets_[bucket_index];
  for (auto it = begin; it != end; ++it, ++bucket.count) {
    bucket.x[bucket.count] = it->x();
    bucket.y[bucket.count] = it->y();
    bucket.z[bucket.count] = it->z();
  }
  Node& self = nodes_[node];
  self.child[0] = self.child[1] = -1;
  self.bucket = bucket_index;
  self.tree_deleted = 0;
  PullUp(node);
}

// Recomputes a node's counters and box from its children (internal) or its bucket (leaf).
void IkdTree::PullUp(int node) {
  Node& self = nodes_[node];
  self.tree_deleted = 0;
  if (self.IsLeaf()) {
    const Bucket& bucket = buckets_[self.bucket];
    self.size = static_cast<int32_t>(bucket.count);
    self.invalid = __builtin_popcount(bucket.deleted);
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(kInf);
    Eigen::Vector3f hi = Eigen::Vector3f::Constant(-kInf);
    for (uint32_t i = 0; i < bucket.count; ++i) {
      if ((bucket.deleted >> i) & 1u) continue;
      const Eigen::Vector3f p(bucket.x[i], bucket.y[i], bucket.z[i]);
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    for (int a = 0; a < 3; ++a) {
      self.lo[a] = lo[a];
      self.hi[a] = hi[a];
    }
    return;
  }
  const Node& left = nodes_[self.child[0]];
  const Node& right = nodes_[self.child[1]];
  self.size = left.size + right.size;
  self.invalid = left.invalid + right.invalid;
  for (int a = 0; a < 3; ++a) {
    self.lo[a] = std::min(left.lo[a], right.lo[a]);
    self.hi[a] = std::max(left.hi[a], right.hi[a]);
  }
}

// Hands a lazy "subtree deleted" label one level down (paper: PushDown).
void IkdTree::PushDown(int node) {
  Node& self = nodes_[node];
  if (!self.tree_deleted || self.IsLeaf()) return;
  for (int side = 0; side < 2; ++side) {
    Node& child = nodes_[self.child[side]];
    child.invalid = child.size;
    if (child.IsLeaf()) {
      Bucket& bucket = buckets_[child.bucket];
      bucket.deleted = bucket.count >= 32 ? ~0u : (1u << bucket.count) - 1u;
    } else {
      child.tree_deleted = 1;
    }
  }
  self.tree_deleted = 0;
}

void IkdTree::CollectValid(int node, PointCloud* points) const {
  const Node& self = nodes_[node];
  if (self.invalid == self.size) return;
  if (!self.IsLeaf()) {
    CollectValid(self.child[0], points);
    CollectValid(self.child[1], points);
    return;
  }
  const Bucket& bucket = buckets_[self.bucket];
  for (uint32_t i = 0; i < bucket.count; ++i) {
    if (!((bucket.deleted >> i) & 1u)) points->emplace_back(bucket.x[i], bucket.y[i], bucket.z[i]);
  }
}

PointCloud IkdTree::Flatten() const {
  PointCloud points;
  points.reserve(Size());
  CollectValid(root_, &points);
  return points;
}

std::size_t IkdTree::Size() const {
  const Node& root = nodes_[root_];
  return static_cast<std::size_t>(root.size - root.invalid);
}

std::size_t IkdTree::MemoryBytes() const {
  return nodes_.capacity() * sizeof(Node) + buckets_.capacity() * sizeof(Bucket) +
         (free_nodes_.capacity() + free_buckets_.capacity() + path_.capacity()) * sizeof(int) +
         scratch_points_.capacity() * sizeof(Eigen::Vector3f) +
         cache_sets_.capacity() * sizeof(CacheSet) + occupancy_.capacity();
}

int IkdTree::Depth() const {
  if (Size() == 0 && nodes_[root_].IsLeaf()) return buckets_[nodes_[root_].bucket].count ? 1 : 0;
  std::vector<std::pair<int, int>> stack = {{root_, 1}};
  int deepest = 0;
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    if (!nodes_[node].IsLeaf()) {
      stack.push_back({nodes_[node].child[0], depth + 1});
      stack.push_back({nodes_[node].child[1], depth + 1});
    }
  }
  return deepest;
}

}  // namespace hylo::mapping
