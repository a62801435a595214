#pragma once
// The inertial sensor as the estimators see it (section `imu:` of a run configuration): whether
// there is one, its rate, the local gravity and the continuous-time noise model shared by the
// simulator, the IESKF and the smoother.

#include <cstdint>
#include <string>

namespace hylo::estimation {

/// White noise densities and bias random walks, as datasheets and Kalibr state them.
/// Defaults are of the order of a VectorNav VN-100 (gyro 0.0035 deg/s/sqrt(Hz),
/// accel 0.14 mg/sqrt(Hz)).
struct ImuNoise {
  double gyro_noise_density = 6.1e-5;      ///< gyro white noise, rad/s/sqrt(Hz) (>= 0)
  double accel_noise_density = 1.4e-3;     ///< accelerometer white noise, m/s^2/sqrt(Hz) (>= 0)
  double gyro_bias_random_walk = 1.0e-5;   ///< gyro bias random walk, rad/s^2/sqrt(Hz) (>= 0)
  double accel_bias_random_walk = 1.0e-4;  ///< accel bias random walk, m/s^3/sqrt(Hz) (>= 0)

  bool IsValid(std::string* why) const;
};

struct ImuOptions {
  bool enabled = true;         ///< false: no IMU (`imu: none`): constant-velocity model
  double rate_hz = 200.0;      ///< nominal sample rate, Hz (> 0): five missing samples are a gap
  double gravity_mps2 = 9.81;  ///< local gravity magnitude, m/s² ([9.7, 9.9]: on Earth)
  ImuNoise noise;              ///< continuous-time noise densities
  /// Full-scale ranges: a sample reading at least this on any axis is clipped (its true value
  /// is unknown), so it is dropped and counted like a missing one. The defaults are the widest
  /// ranges common MEMS parts offer (16 g, 2000 deg/s), which never flag an unclipped sample;
  /// set the value a narrower sensor reports when clipped. 0 = no check.
  double accel_range_mps2 = 156.9;  ///< m/s² (>= 2 g when set: gravity alone must fit)
  double gyro_range_radps = 34.9;   ///< rad/s (>= 0)

  bool IsValid(std::string* why) const;
  /// Consecutive IMU stamps farther apart than this are a gap: five missing samples, ns.
  int64_t GapNs() const;
};

}  // namespace hylo::estimation
