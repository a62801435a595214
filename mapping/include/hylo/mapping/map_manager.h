#pragma once
// The map the estimators register against: points added during the run live in one ikd-tree
// that follows the vehicle (a local window: boxes that fall too far behind are deleted, as in
// FAST-LIO2 Sec. V-B), and an optional prior map lives in a second tree that the window never
// touches. Two trees rather than a per-point flag: a box delete on one tree can then never
// remove a prior point, by construction, and the run's tree stays small. Queries merge both.
//
// A streamed prior (streamed_prior.h; a tiled map, hylo::tiles) replaces the second tree by
// the part held around the vehicle: BeginScan posts the position and swaps in what finished
// loading (files, thinning and tree builds stay off the scan path). On demand (the start, a
// lost vehicle), the parts not held are read synchronously. Points the window drops from the
// run's tree can be kept (hybrid mode over a tiled map: they are written back as tiles at the
// end).

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/mapping/ikd_tree.h"
#include "hylo/mapping/streamed_prior.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::mapping {

struct MapManagerOptions {
  double voxel_size_m = 0.5;     ///< on-tree downsampling of added points, m (> 0)
  double window_size_m = 300.0;  ///< side of the local cube kept around the vehicle, m;
                                 ///< 0 disables the window (keep everything)
  double window_margin_m = 100.0;///< move the window when the vehicle comes closer than this
                                 ///< to a face, m (0 < margin < window_size_m / 2)
  bool IsValid(std::string* why) const;
};

/// Counters of what the map did, for the run summary.
struct MapCounters {
  std::size_t scans_added = 0;
  std::size_t points_inserted = 0;
  std::size_t points_windowed_out = 0;  ///< run points deleted by window moves
  std::size_t window_moves = 0;
};

class MapManager final : public registration::NeighborSearch {
 public:
  /// Throws hylo::InternalError naming the field when `options` is not valid.
  explicit MapManager(const MapManagerOptions& options);

  /// Replaces the prior map (map frame, downsampled by the caller). Never windowed.
  void SetPrior(const PointCloud& points_map);

  // --- a streamed prior (map frame = its local frame) ---
  /// Replaces the prior by `prior` (not null), taking whatever part it already holds.
  void SetStreamedPrior(std::shared_ptr<StreamedPrior> prior);
  bool streamed() const { return streamed_ != nullptr; }
  /// Scan path, before the scan's queries: posts `position_map` to a streamed prior, which
  /// swaps in what it finished loading since the last call. Nothing otherwise.
  void BeginScan(const Eigen::Vector3f& position_map);
  /// True without a streamed prior, else whether `position_map` lies on it.
  bool OnPriorMap(const Eigen::Vector3f& position_map) const;
  /// A streamed prior's first load failure ("" when none, or without one).
  std::string prior_error() const;
  /// A streamed prior's queries also read what it does not hold (StreamedPrior::SetOnDemand).
  void SetOnDemand(bool on_demand);
  const StreamedPrior* streamed_prior() const { return streamed_.get(); }
  /// Keep the points the window deletes from the run's tree (windowed_out()).
  void KeepWindowedOut(bool keep) { keep_windowed_out_ = keep; }
  const PointCloud& windowed_out() const { return windowed_out_; }

  /// Moves the window if `sensor_position_map` is near its face, then inserts `points_map`
  /// (downsampled on the tree at voxel_size_m).
  IkdTree::InsertSummary AddScan(const PointCloud& points_map,
                                 const Eigen::Vector3f& sensor_position_map);

  void KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                std::vector<registration::Neighbor>* neighbors) const override;
  std::size_t Size() const override;

  /// Points of the prior the queries see: the whole prior, or the tiles held now.
  std::size_t prior_size() const;
  std::size_t run_size() const { return run_.Size(); }
  /// Every point (prior then run), map frame.
  PointCloud Flatten() const;
  /// Points added during the run only.
  PointCloud FlattenRun() const { return run_.Flatten(); }
  std::size_t MemoryBytes() const;
  const MapCounters& counters() const { return counters_; }
  /// The current window (valid once a scan was added with the window enabled).
  const Box3f& window() const { return window_; }

 private:
  void UpdateWindow(const Eigen::Vector3f& sensor_position_map);

  MapManagerOptions options_;
  IkdTree run_;
  std::unique_ptr<IkdTree> prior_;
  std::shared_ptr<StreamedPrior> streamed_;  // replaces prior_ when set
  bool keep_windowed_out_ = false;
  PointCloud windowed_out_;
  MapCounters counters_;
  bool window_set_ = false;
  Box3f window_;
};

}  // namespace hylo::mapping
