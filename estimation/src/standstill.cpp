#include "hylo/estimation/standstill.h"

#include <cmath>
#include <limits>

#include "hylo/common/option_checks.h"

namespace hylo::estimation {

bool StandstillOptions::IsValid(std::string* why) const {
  return ((std::isfinite(max_spread_ratio) && max_spread_ratio >= 1.0) ||
          FailOption("max_spread_ratio", max_spread_ratio, "must be finite and >= 1", why)) &&
         CheckPositive("max_speed_mps", max_speed_mps, why) &&
         CheckPositive("velocity_noise_mps", velocity_noise_mps, why) &&
         (min_samples >= 3 || FailOption("min_samples", min_samples, "must be >= 3", why));
}

namespace {

// The largest of the three axes' sample standard deviations: motion along one axis must not be
// averaged away by two quiet ones.
double LargestAxisSpread(const std::vector<Eigen::Vector3d>& values) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : values) mean += v;
  mean /= static_cast<double>(values.size());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : values) sum += (v - mean).cwiseAbs2();
  return std::sqrt(sum.maxCoeff() / static_cast<double>(values.size() - 1));
}

double Ratio(double spread, double expected) {
  return expected > 0.0 ? spread / expected : std::numeric_limits<double>::infinity();
}

}  // namespace

StandstillTest TestStandstill(const std::vector<ImuSample>& samples, int64_t t0_ns, int64_t t1_ns,
                              double speed_mps, const ImuOptions& imu,
                              const StandstillOptions& options) {
  StandstillTest test;
  test.speed_mps = speed_mps;
  if (!options.enabled || !imu.enabled) return test;
  std::vector<Eigen::Vector3d> accel, gyro;
  for (const ImuSample& s : samples) {
    if (s.t_ns < t0_ns || s.t_ns > t1_ns) continue;
    accel.push_back(s.accel_imu);
    gyro.push_back(s.gyro_imu);
  }
  test.samples = static_cast<int>(accel.size());
  if (test.samples < options.min_samples) return test;
  // White noise of density d sampled at rate f has a standard deviation of d·√f per sample.
  const double sqrt_rate = std::sqrt(imu.rate_hz);
  test.accel_ratio = Ratio(LargestAxisSpread(accel), imu.noise.accel_noise_density * sqrt_rate);
  test.gyro_ratio = Ratio(LargestAxisSpread(gyro), imu.noise.gyro_noise_density * sqrt_rate);
  test.at_rest = test.accel_ratio <= options.max_spread_ratio &&
                 test.gyro_ratio <= options.max_spread_ratio && std::isfinite(speed_mps) &&
                 speed_mps <= options.max_speed_mps;
  return test;
}

}  // namespace hylo::estimation
