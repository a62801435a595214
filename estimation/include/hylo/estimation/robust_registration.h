#pragma once
// A wide-basin scan-to-map alignment that runs before a back-end's own lidar update, so that
// a sensor whose motion between two scans departs far from the motion model (a hand-held
// lidar at 2 Hz turns up to ~50° more or less than the constant-velocity prediction) starts
// that update from a pose it can converge from. Lidar-only; shared by every back-end.
//
//   1. A coarse subset of the scan (one point per coarse voxel) is aligned by robust
//      point-to-plane ICP. The correspondence gate and the kernel scale come from the
//      observed deviation of the motion model (KISS-ICP's adaptive threshold: Vizzo et al.,
//      "KISS-ICP", RA-L 2023, Sec. III-C), and the kernel is halved each time the alignment
//      settles (coarse to fine), down to a few decimetres.
//   2. The result is checked with the alignment's own evidence: the fraction of the subset
//      within a decimetre of its map plane. A fraction well below what recent accepted scans
//      achieved means a wrong basin; then the alignment is retried wider, from yaw hypotheses
//      about the map z axis around the prediction (a carried sensor turns mostly about the
//      vertical), each aligned on a sparser subset, and the hypothesis with the most inliers
//      is refined and kept if it beats the first result. The first alignment of a run has
//      nothing to compare with and always retries.
//   3. The back-end's update refines from that pose with its usual gate and full scan, and
//      reports its final pose back (Observe), which feeds the adaptive threshold.
// BackendBase::UpdateStart and LearnFromUpdate are where both back-ends call it.

#include <deque>
#include <string>
#include <vector>

#include "hylo/lie/se3.h"
#include "hylo/estimation/nav_state.h"
#include "hylo/registration/plane_matcher.h"
#include "hylo/common/point_types.h"

namespace hylo::estimation {

/// Section `robust_registration:` of a run configuration. Off by default: with an IMU the
/// prediction is good and the back-ends' own update suffices.
struct RobustRegistrationOptions {
  bool enabled = false;         ///< align before each lidar update (no-IMU use)
  double coarse_voxel_m = 1.5;  ///< one point per voxel of this edge forms the subset, m (> 0)
  int max_iterations = 40;      ///< ICP iterations of one alignment (all scales), >= 1
  /// Deviation of the motion model assumed until one was observed (KISS-ICP's initial
  /// threshold), m (> 0).
  double initial_deviation_m = 2.0;
  /// Deviations below this are not learnt from (a sensor at rest says nothing about how far
  /// the model can be off; KISS-ICP's min_motion_th), m (>= 0).
  double min_deviation_m = 0.1;
  /// Narrowest kernel scale, m (> 0): the alignment stops there and the back-end's update,
  /// with its own gate and every scan point, takes the last centimetres.
  double final_kernel_m = 0.2;
  double settle_fraction = 0.05;  ///< see PlaneIcpSettings::settle_fraction (> 0)
  /// Quality check: a point is an inlier when it lies within this of its map plane, m (> 0).
  double inlier_distance_m = 0.1;
  /// ... and the alignment is accepted when its inlier fraction is at least this share of the
  /// median of the recently aligned scans' (0..1; 0: only the first alignment retries).
  double min_inlier_share = 0.8;
  int inlier_history = 10;            ///< aligned scans that median covers, >= 1
  double retry_yaw_range_deg = 60.0;  ///< retries: yaw offsets within ±this, deg (0..180)
  double retry_yaw_step_deg = 15.0;   ///< ... at this step, deg (> 0)

  bool IsValid(std::string* why) const;
};

/// What one Align did.
struct RobustAlignment {
  lie::SE3d T_map_lidar;          ///< the start for the back-end's update
  double deviation_m = 0.0;       ///< motion-model deviation scale used (gate = 3×), m
  int iterations = 0;             ///< ICP iterations over all attempts
  int attempts = 0;               ///< ICP runs: 1 = the prediction held; more = retried
  std::size_t subset_points = 0;  ///< points of the coarse subset
  double inlier_ratio = 0.0;      ///< inliers ÷ subset points at the chosen pose
  double reference_ratio = 0.0;   ///< median of the accepted history (0 = none yet)
  bool passed = true;             ///< the check held, or there was nothing to check against
                                  ///< yet (false: the best hypothesis was kept anyway)
};

struct PlaneIcpSettings {
  double gate_m = 1.0;           ///< |r| beyond this: not used, m
  double kernel_m = 0.3;         ///< first kernel scale, m
  double final_kernel_m = 0.05;  ///< last kernel scale, m
  int max_iterations = 40;       ///< over all scales
  /// A scale has settled when a step moves the points (translation + arc at the median
  /// range) by less than this fraction of the kernel scale.
  double settle_fraction = 0.05;
  double inlier_m = 0.1;  ///< points this close to their plane count as inliers, m
};
struct PlaneIcpResult {
  lie::SE3d T_map_lidar;
  int iterations = 0;
  std::size_t matches = 0;  ///< in the last iteration
  /// Points within settings.inlier_m of their plane at the last association (before the
  /// last, settled step).
  std::size_t inliers = 0;
  bool converged = false;  ///< at the last scale
};
/// Robust point-to-plane ICP of `points_lidar` to the map planes from `T_start`: residuals
/// gated at `gate_m` and weighted by a Geman-McClure kernel whose scale starts at `kernel_m`
/// and halves each time the steps settle, until `final_kernel_m`.
PlaneIcpResult AlignPointToPlane(const PointCloud& points_lidar,
                                 const lie::SE3d& T_start, const registration::PlaneMatcher& planes,
                                 const PlaneIcpSettings& settings);

/// `x` moved so that its lidar frame sits at `T_map_lidar` (extrinsic and the rest kept).
NavState WithLidarPose(const NavState& x, const lie::SE3d& T_map_lidar);

/// KISS-ICP's model error of a pose deviation: translation plus the chord a point at
/// `max_range_m` sweeps under the rotation, m.
double ModelDeviation(const lie::SE3d& deviation, double max_range_m);

class RobustRegistration {
 public:
  /// Throws hylo::InternalError naming the field when `options` is not valid.
  explicit RobustRegistration(const RobustRegistrationOptions& options);

  bool enabled() const { return options_.enabled; }

  /// Aligns a (downsampled) scan from the motion model's prediction.
  RobustAlignment Align(const PointCloud& points_lidar,
                        const lie::SE3d& T_map_lidar_predicted,
                        const registration::PlaneMatcher& planes);

  /// The back-end's final pose for the scan last aligned: its deviation from the prediction
  /// feeds the adaptive threshold, and the alignment's inlier fraction the quality history.
  void Observe(const lie::SE3d& T_map_lidar_predicted, const lie::SE3d& T_map_lidar_final);

  /// The current motion-model deviation scale, m.
  double Deviation() const;

 private:
  RobustRegistrationOptions options_;
  double max_range_m_ = 0.0;       // of the last aligned scan's subset
  double last_ratio_ = 0.0;        // inlier fraction of the last alignment
  double sum_sq_deviation_ = 0.0;  // KISS-ICP: Σ e² over the learnt deviations
  int num_deviations_ = 0;
  std::deque<double> inlier_history_;  // inlier fractions of accepted scans
};

}  // namespace hylo::estimation
