#pragma once
// Settings of the sliding-window Ceres smoother back-end (section `sliding_window:` of a run
// configuration). What both back-ends share lives in LidarUpdateOptions and NoImuOptions.

#include <string>

#include "hylo/registration/robust_kernel.h"

namespace hylo::estimation {

struct SlidingWindowOptions {
  /// The Ceres linear solvers the configuration may name (all run single-threaded here).
  enum class LinearSolver {
    kSparseNormalCholesky,  ///< sparse_normal_cholesky (SuiteSparse)
    kDenseNormalCholesky,   ///< dense_normal_cholesky
    kDenseSchur,            ///< dense_schur
    kSparseSchur,           ///< sparse_schur
    kDenseQr,               ///< dense_qr
  };
  /// Robust loss on the point-to-plane residuals: the kernels of every solver of the project.
  using RobustLoss = registration::RobustKernel::Type;

  int window_size = 10;             ///< states (scans) optimised together, >= 2
  int max_iterations = 6;           ///< Ceres iterations per association round, >= 1
  double max_solver_time_s = 0.05;  ///< wall-time budget of all rounds of one scan, s (> 0)
  LinearSolver linear_solver = LinearSolver::kSparseNormalCholesky;
  /// Solver rounds per scan, >= 1; the robust weights of all scans are recomputed before each,
  /// and the newest scan's planes searched again where rematch_threshold says.
  int association_rounds = 2;
  /// A round searches the newest scan's planes again only when a pose of the window moved by
  /// more than this since they were last searched, m or rad (the filter's rematch_threshold,
  /// same value); 0: search before every round. >= 0.
  double rematch_threshold = 0.01;
  /// Default none: the matches already pass the range-scaled gate of PlaneMatcher, the IESKF's
  /// only outlier model, so both back-ends see the same measurement model (on simulator
  /// session A, Huber at 0.05 m doubled the end drift: 0.35 % against 0.18 %).
  RobustLoss robust_loss = RobustLoss::kNone;
  double robust_loss_scale_m = 0.05;  ///< residual where the robust loss bends, m (> 0)
  /// Marginalise the oldest state into a Gaussian prior (true) or simply drop it (false: only
  /// for comparisons, the window then forgets what the dropped states knew).
  bool marginalize = true;
  /// Constraints between the scans of the window: points of each new scan matched to planes
  /// of every earlier scan of the window, fitted in that scan's own frame, so the plane moves
  /// with the pose of the scan that saw it (ScanPairFactor). Off by default: on the scenario
  /// matrix they cost twice the CPU and made localization and most SLAM runs worse
  /// (docs/results.md). Off, the window's scans fill in the map's gaps at their current
  /// estimates instead (the map holds finalized scans only).
  bool scan_pairs = false;
  /// Most points of the new scan matched to each earlier scan (evenly spread over the scan),
  /// >= 1: each pair costs a neighbour search per point and round, and a window's pairs
  /// grow with the square of its size.
  int pair_points = 400;

  /// Online calibration (needs an IMU): the lidar-IMU clock offset and a small rotation of the
  /// extrinsic, estimated with the window's states as corrections to the configured values,
  /// each held by a Gaussian prior at the configured value (Estimator::Calibration). Off by
  /// default: both are observable only while the vehicle turns and accelerates, and a
  /// configuration that is right gains nothing from them.
  bool estimate_time_offset = false;
  bool estimate_extrinsic_rotation = false;
  double time_offset_prior_sigma_s = 0.05;            ///< prior on the correction, s (> 0)
  double extrinsic_rotation_prior_sigma_rad = 0.035;  ///< ... per axis, rad (> 0), about 2°

  bool EstimatesCalibration() const { return estimate_time_offset || estimate_extrinsic_rotation; }

  /// The kernel of robust_loss at robust_loss_scale_m.
  registration::RobustKernel Kernel() const { return {robust_loss, robust_loss_scale_m}; }

  bool IsValid(std::string* why) const;

 private:
  bool CheckCalibrationWithoutPairs(std::string* why) const;
};

/// Configuration names of the enums ("sparse_normal_cholesky", ..., "none", "huber",
/// "cauchy", "geman_mcclure"); Parse* return false for an unknown name.
std::string ToString(SlidingWindowOptions::LinearSolver solver);
bool ParseLinearSolver(const std::string& name, SlidingWindowOptions::LinearSolver* solver);
std::string ToString(SlidingWindowOptions::RobustLoss loss);
bool ParseRobustLoss(const std::string& name, SlidingWindowOptions::RobustLoss* loss);

}  // namespace hylo::estimation
