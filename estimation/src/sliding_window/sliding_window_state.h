#pragma once
// The sliding window's per-scan state and the factor graph built over it (private).

#include <deque>
#include <memory>
#include <vector>

#include "hylo/estimation/estimator_options.h"
#include "hylo/estimation/imu_preintegration.h"
#include "hylo/mapping/ikd_tree.h"
#include "marginalization.h"
#include "sliding_window_factors.h"

namespace hylo::estimation {

struct WindowState;

/// One scan's points matched to planes of an earlier scan of the window (each plane in that
/// scan's IMU frame: ScanPairFactor).
struct ScanPairMatches {
  WindowState* earlier = nullptr;
  std::vector<PlaneMatch> matches;
};

struct WindowState {
  int64_t t_ns = 0;
  /// A scan was registered at this state and it was not finalized yet (a start state holds
  /// none: it is not a scan's pose).
  bool holds_scan = false;
  StateBlocks blocks;
  /// The IMU showed rest since the previous state: a zero-velocity factor holds it.
  bool at_rest = false;
  /// Preintegrated IMU from the previous window state to this one (null for the first state
  /// of a window, and without IMU data).
  std::unique_ptr<ImuPreintegration> imu;
  std::vector<Eigen::Vector3d> points_imu;  ///< the scan, IMU frame at t_ns, m
  std::vector<double> ranges_m;             ///< each point's range from the lidar, m
  std::vector<PlaneMatch> matches;          ///< current plane matches (empty: no lidar factor)
  /// points_imu, searchable: the later scans of the window search it (null without a scan).
  std::unique_ptr<mapping::IkdTree> own_points;
  /// This scan's points against the planes of earlier scans of the window, found while it was
  /// the newest; a pair goes when its earlier scan leaves the window.
  std::vector<ScanPairMatches> pairs;
};

using Window = std::deque<std::unique_ptr<WindowState>>;

/// Cost functions (owned) and their blocks for every factor of the window.
struct FactorSet {
  std::vector<std::unique_ptr<ceres::CostFunction>> owned;
  std::vector<FactorRef> refs;
};

/// The window's blocks as BlockRefs: rotation, position (and speed_bias with an IMU).
std::vector<BlockRef> StateBlockRefs(WindowState* state, bool use_imu);

/// Every factor of the window: the prior (if any), IMU factors (using the shared gravity block
/// `gravity_map`) or constant-velocity factors, zero-velocity factors of states at rest, the
/// point-to-plane factors of scans with matches, and those between scans (pairs).
FactorSet BuildFactors(const Window& window, const MarginalPrior* prior, double* gravity_map,
                       const EstimatorOptions& options, bool use_imu);

/// True when `factor` uses any of `blocks`' values.
bool Touches(const FactorRef& factor, const std::vector<BlockRef>& blocks);

}  // namespace hylo::estimation
