// IMU measurement model.
#include "hylo/sim/imu_model.h"

#include <cmath>
#include <sstream>

namespace hylo::sim {

bool ImuOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(rate_hz > 0.0 && rate_hz <= 10000.0))
    os << "rate_hz = " << rate_hz << " must be in (0, 10000]";
  else if (!(gravity_mps2 > 0.0))
    os << "gravity_mps2 = " << gravity_mps2 << " must be > 0";
  else if (!(accel_noise_density >= 0.0 && gyro_noise_density >= 0.0 &&
             accel_bias_random_walk >= 0.0 && gyro_bias_random_walk >= 0.0 &&
             accel_bias_initial_sigma >= 0.0 && gyro_bias_initial_sigma >= 0.0))
    os << "noise densities, random walks and initial bias sigmas must be >= 0";
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

ImuOptions ImuOptions::NoiseFree() const {
  ImuOptions clean = *this;
  clean.accel_noise_density = clean.gyro_noise_density = 0.0;
  clean.accel_bias_random_walk = clean.gyro_bias_random_walk = 0.0;
  clean.accel_bias_initial_sigma = clean.gyro_bias_initial_sigma = 0.0;
  return clean;
}

int64_t ImuOptions::period_ns() const { return std::llround(1e9 / rate_hz); }

ImuSample TrueImuSample(const KinematicState& state, double gravity_mps2, int64_t t_ns) {
  ImuSample sample;
  sample.t_ns = t_ns;
  // Specific force: what an accelerometer reads, f = R^T (a - g_vec), g_vec = (0, 0, -g).
  sample.accel_imu =
      state.R_map_imu.transpose() * (state.accel_map + Eigen::Vector3d(0.0, 0.0, gravity_mps2));
  sample.gyro_imu = state.omega_imu;
  return sample;
}

ImuSimulator::ImuSimulator(const ImuOptions& options, Rng rng) : options_(options), rng_(rng) {
  accel_bias_ = Gaussian3(options.accel_bias_initial_sigma);
  gyro_bias_ = Gaussian3(options.gyro_bias_initial_sigma);
}

Eigen::Vector3d ImuSimulator::Gaussian3(double sigma) {
  if (sigma == 0.0) return Eigen::Vector3d::Zero();  // no draws: noise-free stays exact
  const double x = rng_.Gaussian(sigma), y = rng_.Gaussian(sigma), z = rng_.Gaussian(sigma);
  return {x, y, z};
}

ImuSample ImuSimulator::Measure(const KinematicState& state, int64_t t_ns) {
  const double dt = 1.0 / options_.rate_hz;
  ImuSample sample = TrueImuSample(state, options_.gravity_mps2, t_ns);
  sample.accel_imu += accel_bias_ + Gaussian3(options_.accel_noise_density / std::sqrt(dt));
  sample.gyro_imu += gyro_bias_ + Gaussian3(options_.gyro_noise_density / std::sqrt(dt));
  accel_bias_ += Gaussian3(options_.accel_bias_random_walk * std::sqrt(dt));
  gyro_bias_ += Gaussian3(options_.gyro_bias_random_walk * std::sqrt(dt));
  return sample;
}

}  // namespace hylo::sim
