#pragma once
// Incremental kd-tree map after the ikd-tree of Cai, Xu and Zhang ("ikd-Tree: An Incremental
// K-D Tree for Robotic Applications", arXiv 2102.10808): points are inserted and deleted in
// place, boxes are deleted with lazy labels, and a subtree that breaks the balance (alpha_bal)
// or deletion (alpha_del) criterion is rebuilt, so the map never needs a full rebuild per scan.
//
// Departures from the paper, and why:
// - Leaves are buckets of up to kBucketCapacity points stored coordinate by coordinate, not
//   one point per node: a 5-NN query then scans a few contiguous points instead of chasing
//   one pointer per point, which is what keeps queries near a static tree's speed. Every
//   node keeps a box around its valid points and searches prune by boxes only, so split
//   planes serve insertion routing and balance, never correctness.
// - A downsampling insert whose voxel holds exactly one map point moves that point's slot to
//   the new point (widening the boxes above it) instead of delete + insert: same map, no
//   deleted slot left behind, so no deletion-triggered rebuild is owed.
// - The down-sampling insert first asks a small voxel cache (recently used voxels known to hold
//   exactly one valid point, and that point) and per-voxel-hash occupancy counts (a zero proves
//   a voxel empty), and searches the tree only when neither answers; every update keeps both
//   exact, in bounded memory (<= 10 B/point for the cache, capped by
//   Options::voxel_cache_max; 2-4 B/point for the counts), see ikd_tree_voxel_index.cpp.
// - Rebuilds are synchronous (on the calling thread). The paper moves large rebuilds to a
//   second thread to bound the worst-case latency of one update; that needs an operation log
//   replayed under a lock. Here a rebuild costs at most the size of the violating subtree
//   (O(n log n)), amortised O(log n) per update; the benchmark reports the worst step.
//
// Thread safety: const methods may run concurrently with each other; any modification needs
// exclusive access (no const method keeps mutable state).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/common/voxel_key.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::mapping {

/// Axis-aligned closed box [min, max] in map coordinates, m.
struct Box3f {
  Eigen::Vector3f min = Eigen::Vector3f::Zero();  ///< lower corner, m
  Eigen::Vector3f max = Eigen::Vector3f::Zero();  ///< upper corner, m (inclusive)
};

class IkdTree final : public registration::NeighborSearch {
 public:
  static constexpr int kBucketCapacity = 32;  ///< most points one leaf holds (<= 32: bit mask)

  struct Options {
    float alpha_balance = 0.7f;  ///< alpha_bal: rebuild when a child holds more than this
                                 ///< fraction of its parent's points, in (0.5, 1)
    float alpha_delete = 0.5f;   ///< alpha_del: rebuild when more than this fraction of a
                                 ///< subtree's points are deleted, in (0, 1)
    int leaf_size = 24;          ///< most points per leaf after a (re)build, 1..kBucketCapacity
    int min_checked_size = 64;   ///< subtrees with fewer stored points are never rebuilt by
                                 ///< the criteria (searching them is already cheap), >= 2
    int voxel_cache_max = 1 << 16;  ///< most voxels the down-sampling insert's cache holds
                                    ///< (16 B each; it grows to about one per 2 map points
                                    ///< up to this), >= 4, or 0: no cache (every
                                    ///< down-sampling insert searches the tree)
    bool IsValid(std::string* why) const;
  };

  /// What one Insert call did.
  struct InsertSummary {
    std::size_t num_inserted = 0;   ///< points added to the map
    std::size_t num_replaced = 0;   ///< map points removed because a new one was nearer the
                                    ///< voxel centre (downsampling only)
    std::size_t num_skipped = 0;    ///< points not added: their voxel kept a nearer point
    std::size_t num_nonfinite = 0;  ///< NaN/inf points rejected
  };

  /// Counters of the re-balancing work done since construction.
  struct Stats {
    std::size_t num_rebuilds = 0;        ///< partial rebuilds run by the criteria
    std::size_t num_points_rebuilt = 0;  ///< valid points re-sorted by those rebuilds
    std::size_t largest_rebuild = 0;     ///< points of the largest single rebuild
    std::size_t num_voxel_cache_hits = 0;  ///< down-sampling inserts decided by the voxel cache
    std::size_t num_voxels_proven_empty = 0;  ///< down-sampling inserts into a voxel the
                                              ///< occupancy counts proved empty (no search)
    std::size_t num_voxel_searches = 0;    ///< down-sampling inserts decided by a tree search
  };

  IkdTree();
  /// Throws hylo::InternalError naming the field when `options` is not valid.
  explicit IkdTree(Options options);

  /// Replaces the map by `points` (a balanced tree; non-finite points are dropped).
  void Build(const PointCloud& points);

  /// Adds `points`. With voxel_size_m > 0 each voxel keeps only the point nearest its centre
  /// (the paper's down-sampling): a new point replaces the voxel's map points only if it is
  /// strictly nearer the centre than all of them.
  InsertSummary Insert(const PointCloud& points, float voxel_size_m = 0.f);

  /// Deletes every map point exactly equal to one of `points`; returns how many were deleted.
  std::size_t Delete(const PointCloud& points);

  /// Deletes every map point inside `box` (closed); returns how many were deleted.
  std::size_t DeleteBox(const Box3f& box);

  void KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                std::vector<registration::Neighbor>* neighbors) const override;

  /// All map points within `radius` (m) of `query`, nearest first.
  void Radius(const Eigen::Vector3f& query, float radius,
              std::vector<registration::Neighbor>* neighbors) const;

  /// All map points inside `box` (closed), in tree order.
  void BoxSearch(const Box3f& box, PointCloud* points) const;

  /// Number of valid (not deleted) points.
  std::size_t Size() const override;

  /// The valid points, in tree order.
  PointCloud Flatten() const;

  /// Heap bytes held by the tree (node and bucket arrays at their capacity, free lists).
  std::size_t MemoryBytes() const;

  /// Depth of the deepest leaf (root = 1; 0 when empty); for tests and diagnostics.
  int Depth() const;

  /// Checks the counters, lazy labels and boxes of every node (for tests; O(n)).
  bool CheckInvariants(std::string* why) const;

  const Stats& stats() const { return stats_; }
  const Options& options() const { return options_; }

 private:
  // A leaf's points, one array per coordinate so that distances to all slots vectorise.
  // Unused slots hold +inf so that they are never nearer than anything.
  struct Bucket {
    float x[kBucketCapacity];
    float y[kBucketCapacity];
    float z[kBucketCapacity];
    uint32_t count;    // used slots
    uint32_t deleted;  // bit i set: slot i lazily deleted
  };
  struct Node {
    float lo[3];  // box holding every valid point below (may be loose)
    float hi[3];
    int32_t child[2];      // -1 in a leaf
    int32_t bucket;        // leaf: index into buckets_; internal: -1
    int32_t size;          // points stored below, deleted included
    int32_t invalid;       // deleted points stored below
    float split;           // internal: routes inserts (ties to the smaller side); searches
                           // use the boxes, so a point moved in place may cross it
    uint8_t axis;          // internal: split axis
    uint8_t tree_deleted;  // lazy label: the whole subtree is deleted, children not told
    bool IsLeaf() const { return bucket >= 0; }
  };
  // One downsampling insert's question about a voxel: its valid map points (found inside
  // `box`, filtered by VoxelOf == key), how many, and the one nearest the centre.
  struct VoxelScan {
    Box3f box;                          // search box, slightly larger than the voxel
    Eigen::Matrix<int64_t, 3, 1> key;   // the voxel
    Eigen::Vector3f centre;             // its centre, m
    float voxel_size_m = 0.f;
    std::size_t count = 0;              // valid map points in the voxel
    float best_d2 = 0.f;                // squared distance of `best` to the centre, m^2
    Eigen::Vector3f best;               // first point (tree order) nearest the centre
  };

  // ikd_tree_build.cpp
  int NewNode();
  int NewBucket();
  void FreeSubtree(int node);
  void BuildSubtree(int node, PointCloud::iterator begin, PointCloud::iterator end);
  void MakeLeaf(int node, PointCloud::const_iterator begin, PointCloud::const_iterator end);
  void PullUp(int node);
  void PushDown(int node);
  void CollectValid(int node, PointCloud* points) const;
  bool CheckSubtree(int node, bool labelled, std::string* why) const;  // ikd_tree_check.cpp
  // The down-sampling insert's voxel cache: sets of kCacheWays voxels, each known to hold
  // exactly one valid map point, stored here (the voxel is recomputed from it, VoxelOf); the
  // most recently used first. Kept exact by every update; see ikd_tree_voxel_index.cpp.
  static constexpr int kCacheWays = 4;
  struct alignas(64) CacheSet {  // one cache line
    float x[kCacheWays];
    float y[kCacheWays];
    float z[kCacheWays];
    uint32_t tag[kCacheWays];  // hash bits of the way's voxel, odd; 0: unused (and all after)
  };
  struct CacheSlot {  // where a voxel lives in the cache
    std::size_t set;
    uint32_t tag;
  };
  // One k-nearest search in progress (ikd_tree_search.cpp).
  struct KnnSearch;
  // ikd_tree_update.cpp
  void InsertPoint(const Eigen::Vector3f& point);
  void SplitLeaf(int node, const Eigen::Vector3f& point);
  std::size_t DeleteInBox(int node, const Box3f& box, const int64_t* voxel, float voxel_size_m);
  bool ReplacePoint(int node, const Eigen::Vector3f& old_point, const Eigen::Vector3f& new_point);
  // ikd_tree_voxel_index.cpp
  InsertSummary InsertDownsampled(const Eigen::Vector3f& point, float voxel_size_m);
  InsertSummary InsertBySearch(const Eigen::Vector3f& point, float voxel_size_m,
                               Eigen::Vector3f* kept);
  void ResetVoxelCache(float voxel_size_m);
  void GrowVoxelCache();
  CacheSlot CacheSlotOf(const VoxelKey& key) const;
  int FindWay(CacheSlot slot, const VoxelKey& key) const;  // -1: not cached
  void Remember(CacheSlot slot, const VoxelKey& key, const Eigen::Vector3f& point);
  void Forget(const Eigen::Vector3f& point);  // the voxel of `point` changed
  void RecountOccupancy();
  std::size_t OccupancyIndex(const VoxelKey& key) const;
  void CountInVoxel(const VoxelKey& key, int delta);  // `delta` valid points added/removed
  void CountPoint(const Eigen::Vector3f& point, int delta);
  bool CheckVoxelIndex(std::string* why) const;
  // ikd_tree_search.cpp
  void KNearestIn(int node, KnnSearch* search) const;
  void RadiusIn(int node, const Eigen::Vector3f& query, float radius_d2,
                std::vector<registration::Neighbor>* neighbors) const;
  void BoxSearchIn(int node, const Box3f& box, PointCloud* points) const;
  void VoxelSearchIn(int node, VoxelScan* scan) const;
  // ikd_tree_rebuild.cpp
  bool BreaksCriteria(const Node& node) const;
  void RebalancePath(const std::vector<int>& path);
  void Rebuild(int node);

  Options options_;
  Stats stats_;
  std::vector<Node> nodes_;
  std::vector<Bucket> buckets_;
  std::vector<int> free_nodes_;
  std::vector<int> free_buckets_;
  int root_ = -1;
  std::vector<int> path_;                    // scratch: root-to-leaf path of an insert
  PointCloud scratch_points_;                // scratch: points of a rebuild
  std::vector<CacheSet> cache_sets_;  // any count (multiply-shift indexing); empty: no cache
  float cache_voxel_m_ = 0.f;          // voxel edge the cache is kept for, m; 0: none
  // Valid points per hash bucket of voxels (saturating at 255, then never decreased): a zero
  // proves a voxel empty without a tree search. Power-of-2 size, >= 2 per valid point.
  std::vector<uint8_t> occupancy_;
};

}  // namespace hylo::mapping
