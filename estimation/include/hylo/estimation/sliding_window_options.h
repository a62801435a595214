#pragma once
// Settings of the sliding-window Ceres smoother back-end (section `sliding_window:` of a run
// configuration).

#include <string>

namespace hylo::estimation {

struct SlidingWindowOptions {
  int window_size = 10;              ///< states (scans) optimised together, >= 2
  int max_iterations = 6;            ///< Ceres iterations per association round, >= 1
  double max_solver_time_s = 0.05;   ///< wall-time budget of all rounds of one scan, s (> 0)
  /// Ceres linear solver: sparse_normal_cholesky (SuiteSparse), dense_normal_cholesky,
  /// dense_schur, sparse_schur or dense_qr.
  std::string linear_solver = "sparse_normal_cholesky";
  /// Solver rounds per scan; the newest scan's planes are searched again (and the robust
  /// weights of all scans recomputed) before each round, >= 1.
  int association_rounds = 2;
  /// Robust loss on the point-to-plane residuals: none, huber or cauchy. Default none: the
  /// matches already pass the range-scaled gate of PlaneMatcher, the IESKF's only outlier
  /// model, so both back-ends see the same measurement model (on simulator session A, Huber
  /// at 0.05 m doubled the end drift: 0.35 % against 0.18 %).
  std::string robust_loss = "none";
  double robust_loss_scale_m = 0.05;  ///< residual where the robust loss bends, m (> 0)
  double lidar_noise_m = 0.02;        ///< σ of one point-to-plane residual, m (> 0)
  int min_matches = 20;               ///< fewer matched points: no correction, scan reported
  /// Marginalise the oldest state into a Gaussian prior (true) or simply drop it (false: only
  /// for comparisons, the window then forgets what the dropped states knew).
  bool marginalize = true;
  // Degeneracy, as IeskfOptions: the smallest eigenvalue of the newest scan's per-match
  // translation information Σ n nᵀ / N (0..1) and rotation information Σ (q×n)(q×n)ᵀ / N (m²).
  double min_translation_information = 0.02;  ///< below: scan flagged degenerate (>= 0)
  double min_rotation_information = 0.05;     ///< below: scan flagged degenerate, m² (>= 0)
  double cv_translation_noise = 1.0;  ///< no-IMU: random walk on velocity, m/s/√s (> 0)
  double cv_rotation_noise = 0.5;     ///< no-IMU: random walk on angular rate, rad/s/√s (> 0)
  /// No-IMU mode only, as IeskfOptions: start the newest pose from the yaw offset (about the
  /// map z axis, within ±this of the constant-velocity prediction) with the most plane
  /// matches, deg (>= 0, <= 180; 0 = off).
  double no_imu_yaw_search_deg = 0.0;
  double no_imu_yaw_search_step_deg = 5.0;  ///< step of that search, deg (> 0)

  bool IsValid(std::string* why) const;
};

}  // namespace hylo::estimation
