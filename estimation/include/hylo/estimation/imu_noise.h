#pragma once
// Continuous-time IMU noise model shared by the simulator, the IESKF and the smoother.

#include <string>

namespace hylo::estimation {

/// White noise densities and bias random walks, as datasheets and Kalibr state them.
/// Defaults are of the order of a VectorNav VN-100 (gyro 0.0035 deg/s/sqrt(Hz),
/// accel 0.14 mg/sqrt(Hz)).
struct ImuNoise {
  double gyro_noise_density = 6.1e-5;     ///< gyro white noise, rad/s/sqrt(Hz)
  double accel_noise_density = 1.4e-3;    ///< accelerometer white noise, m/s^2/sqrt(Hz)
  double gyro_bias_random_walk = 1.0e-5;  ///< gyro bias random walk, rad/s^2/sqrt(Hz)
  double accel_bias_random_walk = 1.0e-4; ///< accel bias random walk, m/s^3/sqrt(Hz)

  /// False (with the reason in *why) when a density is negative or not finite.
  bool IsValid(std::string* why) const;
};

}  // namespace hylo::estimation
