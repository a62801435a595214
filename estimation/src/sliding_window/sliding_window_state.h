#pragma once
// The sliding window's per-scan state and the factor graph built over it (private).

#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "calibration_factors.h"
#include "hylo/estimation/estimator_options.h"
#include "hylo/estimation/imu_preintegration.h"
#include "hylo/lie/se3.h"
#include "hylo/mapping/ikd_tree.h"
#include "marginalization.h"
#include "scan_plane_summary.h"
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
  /// The body rate less the gyro bias about t_ns (the mean since the previous state), rad/s,
  /// IMU frame: how the pose moves over a clock offset.
  Eigen::Vector3d rate_imu = Eigen::Vector3d::Zero();
  /// The IMU showed rest since the previous state: a zero-velocity factor holds it.
  bool at_rest = false;
  /// Preintegrated IMU from the previous window state to this one (null for the first state
  /// of a window, and without IMU data).
  std::unique_ptr<ImuPreintegration> imu;
  std::vector<Eigen::Vector3d> points_imu;  ///< the scan, IMU frame at t_ns, m
  std::vector<double> ranges_m;             ///< each point's range from the lidar, m
  /// Current plane matches (empty: no lidar factor). Whoever changes them or their weights
  /// calls MatchesChanged().
  std::vector<PlaneMatch> matches;
  /// points_imu, searchable: the later scans of the window search it (null without a scan).
  std::unique_ptr<mapping::IkdTree> own_points;
  /// This scan's points against the planes of earlier scans of the window, found while it was
  /// the newest; a pair goes when its earlier scan leaves the window.
  std::vector<ScanPairMatches> pairs;

  /// The matches' cost in closed form, summarized about this state's position when first asked
  /// after they changed: most solves of a window change only the newest scan's matches.
  const ScanPlaneSummary& PlaneSummary() {
    if (!plane_summary_) {
      plane_summary_ =
          ScanPlaneSummary::Of(matches, Eigen::Map<const Eigen::Vector3d>(blocks.position));
    }
    return *plane_summary_;
  }
  void MatchesChanged() { plane_summary_.reset(); }

 private:
  std::optional<ScanPlaneSummary> plane_summary_;
};

using Window = std::deque<std::unique_ptr<WindowState>>;

/// The online calibration's blocks, shared by every scan of the window (calibration_factors.h),
/// and their priors: Gaussian, centred on the configured values (corrections of zero) until a
/// restart of the window, which centres them on the estimate it had reached.
struct WindowCalibration {
  CalibrationLayout layout;
  double time_offset_s[1] = {0.0};                      ///< δt, s
  double extrinsic_rotation[4] = {0.0, 0.0, 0.0, 1.0};  ///< Q (x y z w)
  lie::SE3d T_imu_lidar_configured;
  double time_offset_prior_s = 0.0;
  double extrinsic_rotation_prior[4] = {0.0, 0.0, 0.0, 1.0};
  double time_offset_sigma_s = 0.05;
  double extrinsic_rotation_sigma_rad = 0.035;

  /// The estimated blocks in layout order (time offset, then rotation).
  std::vector<BlockRef> Blocks();
  lie::SO3d RotationCorrection() const;
  /// The extrinsic with the estimated rotation: (Q R_il, t_il).
  lie::SE3d T_imu_lidar() const;
  /// Where the points of the state `x` (IMU frame by the configured extrinsic) lie in the
  /// map: the state moved on by δt at `rate_imu`, after the rotation correction.
  lie::SE3d ObservationPose(const NavState& x, const Eigen::Vector3d& rate_imu) const;
  /// The priors start again at the current estimate.
  void RecentrePriors();
};

/// Cost functions (owned) and their blocks for every factor of the window.
struct FactorSet {
  std::vector<std::unique_ptr<ceres::CostFunction>> owned;
  std::vector<FactorRef> refs;
};

/// The window's blocks as BlockRefs: rotation, position (and speed_bias with an IMU).
std::vector<BlockRef> StateBlockRefs(WindowState* state, bool use_imu);

/// Every factor of the window: the prior (if any), IMU factors (using the shared gravity block
/// `gravity_map`) or constant-velocity factors, zero-velocity factors of states at rest, the
/// point-to-plane factors of scans with matches (with `calibration`, when not null, and its
/// priors), and those between scans (pairs).
FactorSet BuildFactors(const Window& window, const MarginalPrior* prior, double* gravity_map,
                       WindowCalibration* calibration, const EstimatorOptions& options,
                       bool use_imu);

/// True when `factor` uses any of `blocks`' values.
bool Touches(const FactorRef& factor, const std::vector<BlockRef>& blocks);

}  // namespace hylo::estimation
