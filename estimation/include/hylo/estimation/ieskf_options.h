#pragma once
// Settings of the iterated error-state Kalman filter back-end (section `ieskf:` of a run
// configuration).

#include <string>

namespace hylo::estimation {

struct IeskfOptions {
  int max_iterations = 4;               ///< iterated-update steps per scan, >= 1
  double convergence_rotation_rad = 1e-4;   ///< stop when the step rotates less, rad (> 0)
  double convergence_translation_m = 1e-3;  ///< ... and translates less, m (> 0)
  /// Re-associate planes in the next iteration only if the last step moved the pose more
  /// than this (m or rad); smaller steps keep the planes (FAST-LIO2 re-searches on demand).
  double rematch_threshold = 0.01;
  double lidar_noise_m = 0.02;          ///< σ of one point-to-plane residual, m (> 0)
  int min_matches = 20;                 ///< fewer matched points: no correction, scan reported
  bool online_extrinsic = false;        ///< estimate T_imu_lidar in the filter
  /// Degeneracy: smallest eigenvalue of Σ n nᵀ / N (translation information per match, 0..1)
  /// below this flags the scan degenerate (a plane or corridor leaves a direction unseen).
  double min_translation_information = 0.02;
  /// ... or of Σ (p×n)(p×n)ᵀ / N (rotation information per match, m²) below this.
  double min_rotation_information = 0.05;
  // Initial standard deviations of the state (the covariance given at Initialize by the
  // pipeline), and the constant-velocity model used without an IMU.
  double init_rotation_sigma_rad = 0.01;      ///< roll/pitch/yaw, rad (> 0)
  double init_velocity_sigma_mps = 0.05;      ///< m/s (> 0)
  double init_gyro_bias_sigma_radps = 0.01;   ///< rad/s (> 0)
  double init_accel_bias_sigma_mps2 = 0.1;    ///< m/s² (> 0)
  double init_gravity_sigma_mps2 = 0.01;      ///< m/s² (> 0)
  double init_extrinsic_rotation_sigma_rad = 0.01;  ///< rad (> 0)
  double init_extrinsic_translation_sigma_m = 0.02; ///< m (> 0)
  double cv_translation_noise = 1.0;  ///< no-IMU random walk on velocity, m/s/√s (> 0)
  double cv_rotation_noise = 0.5;     ///< no-IMU random walk on angular rate, rad/s/√s (> 0)
  /// No-IMU mode only: before iterating, try yaw offsets about the map z axis within ±this of
  /// the constant-velocity prediction and start from the one with most plane matches (a
  /// hand-held sensor at a low scan rate turns more between scans than plane association can
  /// recover from), deg (>= 0; 0 = off).
  double no_imu_yaw_search_deg = 0.0;
  double no_imu_yaw_search_step_deg = 5.0;  ///< step of that search, deg (> 0)

  bool IsValid(std::string* why) const;
};

}  // namespace hylo::estimation
