#pragma once
// Settings of the iterated error-state Kalman filter back-end (section `ieskf:` of a run
// configuration). What both back-ends share lives in LidarUpdateOptions and NoImuOptions.

#include <string>

namespace hylo::estimation {

struct IeskfOptions {
  int max_iterations = 4;                   ///< iterated-update steps per scan, >= 1
  double convergence_rotation_rad = 1e-4;   ///< stop when the step rotates less, rad (> 0)
  double convergence_translation_m = 1e-3;  ///< ... and translates less, m (> 0)
  /// Re-associate planes in the next iteration only if the last step moved the pose more
  /// than this (m or rad, > 0); smaller steps keep the planes (FAST-LIO2 re-searches on
  /// demand).
  double rematch_threshold = 0.01;
  bool online_extrinsic = false;  ///< estimate T_imu_lidar in the filter

  bool IsValid(std::string* why) const;
};

}  // namespace hylo::estimation
