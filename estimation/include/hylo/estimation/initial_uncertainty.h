#pragma once
// How uncertain the state is when the pipeline starts a back-end (section
// `initial_uncertainty:` of a run configuration): the same start for every back-end, from the
// static IMU initialisation (SLAM) or from an accepted ICP pose in a prior map (localization),
// or from a start on the move (a log that begins while the vehicle drives).

#include <string>

#include "hylo/estimation/nav_state.h"

namespace hylo::estimation {

struct InitialUncertainty {
  double rotation_sigma_rad = 0.01;             ///< roll/pitch/yaw, rad (> 0)
  double velocity_sigma_mps = 0.05;             ///< m/s (> 0)
  double gyro_bias_sigma_radps = 0.01;          ///< rad/s (> 0)
  double accel_bias_sigma_mps2 = 0.1;           ///< m/s² (> 0)
  double gravity_sigma_mps2 = 0.01;             ///< m/s² (> 0)
  double extrinsic_rotation_sigma_rad = 0.01;   ///< T_imu_lidar rotation, rad (> 0)
  double extrinsic_translation_sigma_m = 0.02;  ///< T_imu_lidar translation, m (> 0)
  /// Position after an accepted ICP start or relocalization: the initializer's accuracy (a
  /// few cm), m (> 0). In SLAM the first position defines the map frame and is held tight.
  double localized_position_sigma_m = 0.05;
  /// A start on the move reads gravity from a vehicle that may be accelerating (0.1 g tilts it
  /// by ~6 deg) and knows neither its speed nor its gyro bias (the mean rate is the turn):
  /// roll and pitch, rad (> 0) ...
  double moving_tilt_sigma_rad = 0.1;
  double moving_velocity_sigma_mps = 3.0;  ///< ... velocity, m/s (> 0; a ground vehicle's speed)
  double moving_gyro_bias_sigma_radps = 0.05;  ///< ... gyro bias, rad/s (> 0)

  bool IsValid(std::string* why) const;

  /// The covariance of a SLAM start (order of nav_state.h).
  StateCovariance SlamCovariance() const;
  /// The covariance of a start from an ICP pose in a prior map.
  StateCovariance LocalizedCovariance() const;
  /// The covariance of a start on the move at `start` (SLAM, or searching for a place in a
  /// prior map): tilt about the map's horizontal axes, whatever way the IMU is mounted.
  StateCovariance MovingCovariance(const NavState& start) const;
};

}  // namespace hylo::estimation
