#pragma once
// Sliding-window smoother back-end: the last N scan states (pose, velocity, gyro and accel
// biases) optimised together with Ceres over
//   - IMU preintegration factors between consecutive states (imu_preintegration.h) whose
//     15-row residual includes the bias random walk, or without an IMU a constant-velocity
//     factor over three consecutive poses;
//   - point-to-plane factors of every scan in the window against the shared map planes, each
//     scan's as one factor of 13 residuals that holds its points' cost exactly (a quadratic
//     form in the pose: scan_plane_summary.h), so a solve's cost does not grow with the points;
//   - point-to-plane factors between the scans of the window (scan_pairs): a scan's points
//     against planes of an earlier scan's own points, which move with that scan's pose;
//   - a Gaussian prior from marginalising the states that left the window (marginalization.h).
// With an IMU the gravity vector is estimated too (one block shared by the window, as the
// IESKF's δg); the extrinsic is held at its initial value unless the configuration asks for
// online calibration (sliding_window.estimate_time_offset / estimate_extrinsic_rotation):
// then a clock-offset correction and an extrinsic rotation correction, shared by the window,
// move every scan's points (calibration_factors.h), each under a prior at the configured value,
// and Calibration() reports them with their standard deviations.
//
// Plane association: only the newest scan is associated again between solver rounds, with
// the map and with each earlier scan of the window; older scans keep the matches found while
// they were newest (their residuals still move with their poses, and a pair's with both).
//
// A state is final when it leaves the window (marginalised) or when the log ends (Finish):
// until then each later scan can still correct it, so the finalized trajectory is smoothed
// while the live state is the window's newest. The pipeline adds a scan to the map when its
// state is finalized, at that state (odometry_pipeline.h): the map holds smoothed poses, and
// the window's own scans reach each other through the pairs, not through the map.

#include <deque>
#include <memory>
#include <vector>

#include "hylo/estimation/backend_base.h"

namespace hylo::estimation {

struct WindowState;        // sliding_window_state.h
struct WindowCalibration;  // sliding_window_state.h
struct MarginalPrior;      // marginalization.h
struct BlockRef;           // marginalization.h

class SlidingWindow final : public BackendBase {
 public:
  /// Throws hylo::InternalError naming the field when `options` or `imu` is not valid.
  SlidingWindow(const EstimatorOptions& options, const ImuOptions& imu);
  ~SlidingWindow() override;

  /// Clears the window and starts again from `state` (also used on relocalization).
  void Initialize(const NavState& state, const StateCovariance& covariance) override;
  UpdateSummary Update(const DeskewedScan& scan, const registration::PlaneMatcher& planes) override;
  StateCovariance Covariance() const override { return covariance_; }
  void Finish() override { FinalizeWindow(); }
  OnlineCalibration Calibration() const override;

  /// States currently in the window, oldest first (for tests and diagnostics).
  std::vector<NavState> WindowStates() const;

 private:
  struct SolveReport {
    int iterations = 0;
    bool converged = false;
    bool out_of_time = false;  // stopped at the budget, not converged, iterations left
  };

  void AppendState(const DeskewedScan& scan);  // sliding_window.cpp
  void SetNewestScan(const DeskewedScan& scan);
  void MarginalizeOldest();  // sliding_window.cpp
  void Correct(const DeskewedScan& scan, const registration::PlaneMatcher& planes,
               UpdateSummary* summary);
  void Solve(SolveReport* report, double budget_s);  // sliding_window_solve.cpp
  std::size_t AssociateNewest(const registration::PlaneMatcher& planes);
  void KeepOwnPoints(WindowState* state) const;  // sliding_window_pairs.cpp
  std::size_t AssociatePairs(const registration::PlaneMatcherOptions& options);
  bool HasEarlierScans() const;  // an earlier scan of the window to pair the newest with
  void Reweight();
  /// A match's weight without a robust kernel: 1/σ of the lidar noise, 1/m.
  double LeastSquaresSqrtWeight() const { return 1.0 / options_.lidar_update.lidar_noise_m; }
  std::vector<lie::SE3d> ObservationPoses() const;  // of every state, oldest first
  /// The largest rotation (rad) or translation (m) of a state's observation pose since `poses`.
  double LargestMotionSince(const std::vector<lie::SE3d>& poses) const;
  void FinishUpdate(UpdateSummary* summary);
  void ComputeCovariance();
  NavState StateAt(std::size_t index) const;
  /// Where the points of window state `index` (points_imu) lie in the map: its pose, or with
  /// online calibration the pose the calibration makes of it.
  lie::SE3d ObservationPose(std::size_t index) const;
  std::vector<BlockRef> CalibrationBlocks();  // empty without online calibration
  void FinalizeWindow();                // every scan state still in the window
  std::vector<double*> GlobalBlocks();  // blocks shared by the window (gravity with an IMU)

  // state_ (BackendBase) is the newest state (time, gravity, extrinsic included).
  double gravity_map_[3] = {0.0, 0.0, -9.81};  // estimated gravity block (IMU mode), m/s²
  StateCovariance covariance_ = StateCovariance::Identity();
  StateCovariance initial_covariance_ = StateCovariance::Identity();
  std::deque<std::unique_ptr<WindowState>> window_;  // oldest first; stable block addresses
  std::unique_ptr<MarginalPrior> prior_;
  // Online calibration (null when off); it outlives restarts of the window.
  std::unique_ptr<WindowCalibration> calibration_;
  Eigen::MatrixXd calibration_covariance_;  // of the calibration blocks' tangents
  bool calibration_started_ = false;        // the configured extrinsic was taken
  // AssociateNewest's per-point scratch, kept from scan to scan (no allocation per round).
  std::vector<registration::Plane> point_planes_;
  std::vector<char> point_matched_;
};

}  // namespace hylo::estimation
