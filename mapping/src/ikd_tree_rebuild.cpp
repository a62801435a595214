// IkdTree: the re-balancing criteria and the partial rebuild (the paper's balance and
// deletion criteria). A subtree is rebuilt when one child holds more than alpha_bal of its
// points or more than alpha_del of its points are deleted; the rebuild flattens the valid
// points and builds a balanced subtree in the same root slot, so the parent is untouched.

#include <algorithm>

#include "hylo/mapping/ikd_tree.h"

namespace hylo::mapping {

bool IkdTree::BreaksCriteria(const Node& node) const {
  if (node.size < options_.min_checked_size) return false;
  const float size = static_cast<float>(node.size);
  if (static_cast<float>(node.invalid) > options_.alpha_delete * size) return true;
  if (node.IsLeaf()) return false;
  const int32_t larger = std::max(nodes_[node.child[0]].size, nodes_[node.child[1]].size);
  return static_cast<float>(larger) > options_.alpha_balance * size;
}

// After an insert along `path` (root first): rebuild the highest node that breaks a criterion
// (rebuilding it also repairs everything below it), then refresh the counters above it.
void IkdTree::RebalancePath(const std::vector<int>& path) {
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (!BreaksCriteria(nodes_[path[i]])) continue;
    Rebuild(path[i]);
    for (std::size_t j = i; j-- > 0;) PullUp(path[j]);
    return;
  }
}

void IkdTree::Rebuild(int node) {
  scratch_points_.clear();
  CollectValid(node, &scratch_points_);
  ++stats_.num_rebuilds;
  stats_.num_points_rebuilt += scratch_points_.size();
  stats_.largest_rebuild = std::max(stats_.largest_rebuild, scratch_points_.size());
  const Node old = nodes_[node];
  if (old.IsLeaf()) {
    free_buckets_.push_back(old.bucket);
  } else {
    FreeSubtree(old.child[0]);
    FreeSubtree(old.child[1]);
  }
  nodes_[node].bucket = -1;
  nodes_[node].child[0] = nodes_[node].child[1] = -1;
  BuildSubtree(node, scratch_points_.begin(), scratch_points_.end());
}

}  // namespace hylo::mapping
