#pragma once
// The IMU: specific force and body rate from the true trajectory, plus white noise and a
// bias random walk (continuous-time densities, discretised at the sample rate as in the
// Kalibr IMU noise model: sigma_d = sigma_c / sqrt(dt), bias step = sigma_b * sqrt(dt)).

#include <Eigen/Core>
#include <string>

#include "hylo/common/sensor_data.h"
#include "hylo/sim/random.h"
#include "hylo/sim/trajectory.h"

namespace hylo::sim {

/// Defaults are VN-100-like (datasheet: gyro 0.0035 deg/s/sqrt(Hz), accel 0.14 mg/sqrt(Hz),
/// in-run bias stability 10 deg/h and 0.04 mg); the random walks are set so the bias drifts
/// by about the in-run stability over ~100 s; the turn-on biases are assumptions.
struct ImuOptions {
  double rate_hz = 200.0;                  ///< sample rate, Hz
  double gravity_mps2 = 9.81;              ///< gravity magnitude (map -z), m/s^2
  double accel_noise_density = 1.4e-3;     ///< white noise, m/s^2/sqrt(Hz)
  double gyro_noise_density = 6.1e-5;      ///< white noise, rad/s/sqrt(Hz)
  double accel_bias_random_walk = 4.0e-5;  ///< bias drift, m/s^3/sqrt(Hz)
  double gyro_bias_random_walk = 5.0e-6;   ///< bias drift, rad/s^2/sqrt(Hz)
  double accel_bias_initial_sigma = 0.02;  ///< turn-on bias (1 sigma per axis), m/s^2
  double gyro_bias_initial_sigma = 0.002;  ///< turn-on bias (1 sigma per axis), rad/s

  bool IsValid(std::string* why) const;
  /// Same rate and gravity, every noise and bias zero (the ground-truth IMU).
  ImuOptions NoiseFree() const;
  int64_t period_ns() const;
};

/// Noise-free IMU reading of `state` (accel = R^T (a + g e_z), the specific force).
ImuSample TrueImuSample(const KinematicState& state, double gravity_mps2, int64_t t_ns);

/// Draws noisy samples in time order; the biases evolve from one call to the next.
class ImuSimulator {
 public:
  ImuSimulator(const ImuOptions& options, Rng rng);
  ImuSample Measure(const KinematicState& state, int64_t t_ns);
  const Eigen::Vector3d& accel_bias() const { return accel_bias_; }
  const Eigen::Vector3d& gyro_bias() const { return gyro_bias_; }

 private:
  Eigen::Vector3d Gaussian3(double sigma);

  ImuOptions options_;
  Rng rng_;
  Eigen::Vector3d accel_bias_, gyro_bias_;
};

}  // namespace hylo::sim
