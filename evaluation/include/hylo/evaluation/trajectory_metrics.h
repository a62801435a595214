#pragma once
// Trajectory evaluation against a reference (ground truth): time association, alignment
// (Umeyama SE(3) / Sim(3), or at the first pose), absolute trajectory error (ATE) and relative
// pose error (RPE) over a frame or distance delta, following Sturm et al., "A Benchmark for the
// Evaluation of RGB-D SLAM Systems" (IROS 2012), Sec. VI. `hylo eval ate|rpe` is built on this.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace hylo::evaluation {

/// One pose T_world_body at a time (world = the trajectory's own fixed frame).
struct TimedPose {
  int64_t t_ns = 0;
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
};

/// Pose of `trajectory` (sorted by time) at t_ns: linear interpolation of the position and
/// slerp of the rotation between the bracketing poses. False outside the time span.
bool InterpolatePose(const std::vector<TimedPose>& trajectory, int64_t t_ns,
                     Eigen::Isometry3d* pose);

// ---- Time association ----------------------------------------------------------------------

enum class Association {
  kNearest,      ///< the reference pose with the nearest stamp, if within max_dt_ns
  kInterpolate,  ///< the reference interpolated at the estimate's stamp (see max_gap_ns)
};

struct AssociationOptions {
  Association method = Association::kInterpolate;  ///< how a reference pose is found
  int64_t max_dt_ns = 20'000'000;      ///< kNearest: largest |t_estimate - t_reference|, ns, >= 0
                                       ///< (20 ms, as TUM's associate.py); kInterpolate: a stamp
                                       ///< this close to a reference stamp is always matched
  int64_t max_gap_ns = 1'000'000'000;  ///< kInterpolate: largest interval between the two
                                       ///< bracketing reference poses, ns, > 0 (no
                                       ///< interpolation across a hole in the reference)
  bool IsValid(std::string* why) const;
};

/// Estimate poses with their reference counterparts, in time order.
struct AssociatedPoses {
  std::vector<int64_t> t_ns;                 ///< the estimate's stamps
  std::vector<Eigen::Isometry3d> estimate;   ///< T_world_body of the estimate
  std::vector<Eigen::Isometry3d> reference;  ///< T_world_body of the reference
  std::size_t num_unmatched = 0;             ///< estimate poses without a reference pose
};

/// Pairs each estimate pose with a reference pose (both inputs may be in any order; they are
/// sorted by time; estimate stamps repeated are kept once, the first).
AssociatedPoses Associate(const std::vector<TimedPose>& estimate,
                          const std::vector<TimedPose>& reference,
                          const AssociationOptions& options = {});

// ---- Alignment -----------------------------------------------------------------------------

enum class Alignment {
  kNone,       ///< compare in the given frames
  kFirstPose,  ///< T = reference_0 * estimate_0^-1 (odometry started at a known pose)
  kSE3,        ///< Umeyama without scale on the positions (needs 3 non-collinear positions)
  kSim3,       ///< Umeyama with scale (monocular-like scale drift)
};

struct AlignmentResult {
  bool ok = false;  ///< else see message
  /// R and t of x_ref = s R x_est + t (a rigid transform when scale = 1)
  Eigen::Isometry3d T_reference_estimate = Eigen::Isometry3d::Identity();
  double scale = 1.0;  ///< Sim(3) scale s, else 1
  std::string message;
};

/// The transform that best maps the estimate onto the reference (x_ref ~ s R x_est + t).
AlignmentResult AlignTrajectories(const std::vector<Eigen::Isometry3d>& estimate,
                                  const std::vector<Eigen::Isometry3d>& reference,
                                  Alignment alignment);

/// `T_world_body` moved by an alignment: position s R p + t, rotation R R_body.
Eigen::Isometry3d ApplyAlignment(const AlignmentResult& alignment, const Eigen::Isometry3d& pose);

// ---- Errors --------------------------------------------------------------------------------

/// Summary statistics of a set of errors (0 when empty).
struct ErrorStatistics {
  std::size_t count = 0;
  double rmse = 0.0, mean = 0.0, median = 0.0, std = 0.0, max = 0.0;
};
ErrorStatistics ComputeStatistics(std::vector<double> values);

struct AteOptions {
  AssociationOptions association;         ///< how poses are paired in time
  Alignment alignment = Alignment::kSE3;  ///< applied before the errors are taken
  bool IsValid(std::string* why) const;
};

struct AteResult {
  bool ok = false;  ///< false: too few pairs or alignment failed (see message)
  std::string message;
  std::size_t num_poses = 0;         ///< estimated poses with a reference pose
  std::size_t num_unmatched = 0;     ///< estimated poses without one
  double rmse_m = 0.0;               ///< translation error after alignment: RMSE, m
  double mean_m = 0.0;               ///< mean, m
  double median_m = 0.0;             ///< median, m
  double std_m = 0.0;                ///< population standard deviation, m
  double max_m = 0.0;                ///< largest, m
  double rotation_rmse_deg = 0.0;    ///< angle of R_ref^T R_aligned: RMSE, deg
  double rotation_mean_deg = 0.0;    ///< mean, deg
  double rotation_median_deg = 0.0;  ///< median, deg
  double rotation_max_deg = 0.0;     ///< largest, deg
  double path_length_m = 0.0;        ///< reference distance travelled over the pairs, m
  double end_drift_m = 0.0;          ///< |end position error| aligned at the first pose, m
  double end_drift_percent = 0.0;    ///< end_drift_m / path_length_m * 100
  Eigen::Isometry3d T_reference_estimate = Eigen::Isometry3d::Identity();  ///< alignment used
  double scale = 1.0;                        ///< Sim(3) scale used (1 otherwise)
  std::vector<int64_t> t_ns;                 ///< stamps of the pairs, ns
  std::vector<double> translation_errors_m;  ///< per pair, after alignment, m
};

/// ATE (Sturm et al. Eq. 8) of `estimate` against `reference`; needs 1 pair (kNone), 1
/// (kFirstPose) or 3 (kSE3/kSim3). Bad input gives ok = false and a message, never a throw.
AteResult ComputeAte(const std::vector<TimedPose>& estimate,
                     const std::vector<TimedPose>& reference, const AteOptions& options = {});

enum class DeltaUnit {
  kFrames,  ///< pairs (i, i + delta) of associated poses
  kMeters,  ///< pairs (i, j): j the first pose with reference path length from i >= delta
};

struct RpeOptions {
  AssociationOptions association;       ///< how poses are paired in time
  double delta = 1.0;                   ///< frames (an integer >= 1) or metres (> 0)
  DeltaUnit unit = DeltaUnit::kFrames;  ///< what delta counts
  bool IsValid(std::string* why) const;
};

struct RpeResult {
  bool ok = false;  ///< false: no pair at that delta (see message)
  std::string message;
  std::size_t num_poses = 0;         ///< associated poses
  std::size_t num_pairs = 0;         ///< (i, j) pairs evaluated
  double rmse_m = 0.0;               ///< translation of the relative error: RMSE, m
  double mean_m = 0.0;               ///< mean, m
  double median_m = 0.0;             ///< median, m
  double std_m = 0.0;                ///< population standard deviation, m
  double max_m = 0.0;                ///< largest, m
  double rotation_rmse_deg = 0.0;    ///< angle of the relative error: RMSE, deg
  double rotation_mean_deg = 0.0;    ///< mean, deg
  double rotation_median_deg = 0.0;  ///< median, deg
  double rotation_max_deg = 0.0;     ///< largest, deg
};

/// RPE (Sturm et al. Eq. 5): E_ij = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j) for estimate P and
/// reference Q. Independent of any rigid alignment, so none is applied.
RpeResult ComputeRpe(const std::vector<TimedPose>& estimate,
                     const std::vector<TimedPose>& reference, const RpeOptions& options = {});

const char* ToString(Alignment alignment);

}  // namespace hylo::evaluation
