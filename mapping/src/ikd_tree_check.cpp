// IkdTree::CheckInvariants: the structural invariants the searches rely on, for tests.

#include <sstream>

#include "hylo/mapping/ikd_tree.h"

namespace hylo::mapping {

// Returns false (with a reason) at the first broken invariant below `node`. Under a lazy
// label only the stored counts are checked: the children are allowed to be stale.
bool IkdTree::CheckSubtree(int node, bool labelled, std::string* why) const {
  const Node& self = nodes_[node];
  std::ostringstream os;
  if (self.IsLeaf()) {
    const Bucket& bucket = buckets_[self.bucket];
    if (self.size != static_cast<int32_t>(bucket.count)) os << "leaf size != bucket count";
    if (!labelled && self.invalid != __builtin_popcount(bucket.deleted)) {
      os << "leaf invalid " << self.invalid << " != deleted slots";
    }
    for (uint32_t i = 0; i < bucket.count && os.str().empty() && !labelled; ++i) {
      if ((bucket.deleted >> i) & 1u) continue;
      const float p[3] = {bucket.x[i], bucket.y[i], bucket.z[i]};
      for (int a = 0; a < 3; ++a) {
        if (p[a] < self.lo[a] || p[a] > self.hi[a]) os << "valid point outside leaf box";
      }
    }
  } else {
    const Node& left = nodes_[self.child[0]];
    const Node& right = nodes_[self.child[1]];
    if (self.size != left.size + right.size) os << "size != sum of children";
    const bool below_label = labelled || self.tree_deleted;
    if (self.tree_deleted && self.invalid != self.size) os << "labelled but invalid != size";
    if (!below_label && self.invalid != left.invalid + right.invalid) {
      os << "invalid " << self.invalid << " != children " << left.invalid << "+" << right.invalid;
    }
    for (int a = 0; a < 3 && !below_label; ++a) {
      for (const Node* c : {&left, &right}) {
        if (c->invalid < c->size && (c->lo[a] < self.lo[a] || c->hi[a] > self.hi[a])) {
          os << "child box outside parent box";
        }
      }
    }
    if (os.str().empty() && !CheckSubtree(self.child[0], below_label, why)) return false;
    if (os.str().empty() && !CheckSubtree(self.child[1], below_label, why)) return false;
  }
  if (!os.str().empty()) {
    if (why != nullptr) *why = "node " + std::to_string(node) + ": " + os.str();
    return false;
  }
  return true;
}

bool IkdTree::CheckInvariants(std::string* why) const {
  return CheckSubtree(root_, false, why) && CheckVoxelIndex(why);
}

}  // namespace hylo::mapping
