#include "hylo/estimation/imu_initializer.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "hylo/common/check.h"
#include "hylo/common/time.h"

namespace hylo::estimation {

bool ImuInitializerOptions::IsValid(std::string* why) const {
  const std::pair<const char*, double> positive[] = {
      {"duration_s", duration_s},
      {"max_accel_std_mps2", max_accel_std_mps2},
      {"max_gyro_std_radps", max_gyro_std_radps},
      {"max_gyro_mean_radps", max_gyro_mean_radps},
      {"gravity_tolerance_mps2", gravity_tolerance_mps2}};
  for (const auto& [name, value] : positive) {
    if (std::isfinite(value) && value > 0.0) continue;
    if (why != nullptr) {
      std::ostringstream os;
      os << name << " = " << value << ": must be finite and > 0";
      *why = os.str();
    }
    return false;
  }
  return true;
}

ImuInitializer::ImuInitializer(const ImuInitializerOptions& options, double gravity_mps2)
    : options_(options), gravity_mps2_(gravity_mps2) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("invalid options: " + why);
}

ImuInitializer::Status ImuInitializer::Add(const ImuSample& sample) {
  if (status_ != Status::kCollecting) return status_;
  samples_.push_back(sample);
  if (samples_.back().t_ns - samples_.front().t_ns >= SecondsToNanos(options_.duration_s)) {
    Decide();
  }
  return status_;
}

void ImuInitializer::Decide() {
  const double n = static_cast<double>(samples_.size());
  Eigen::Vector3d accel_mean = Eigen::Vector3d::Zero(), gyro_mean = Eigen::Vector3d::Zero();
  for (const ImuSample& s : samples_) {
    accel_mean += s.accel_imu / n;
    gyro_mean += s.gyro_imu / n;
  }
  double accel_var = 0.0, gyro_var = 0.0;
  for (const ImuSample& s : samples_) {
    accel_var += (s.accel_imu - accel_mean).squaredNorm() / n;
    gyro_var += (s.gyro_imu - gyro_mean).squaredNorm() / n;
  }
  const double accel_std = std::sqrt(accel_var), gyro_std = std::sqrt(gyro_var);
  const bool moving = accel_std > options_.max_accel_std_mps2 ||
                      gyro_std > options_.max_gyro_std_radps ||
                      gyro_mean.norm() > options_.max_gyro_mean_radps;
  // A moving vehicle's mean specific force is gravity plus its mean acceleration: the
  // tolerance then also allows a vehicle speeding up or braking at ~0.2 g.
  const double gravity_tolerance =
      moving ? std::max(options_.gravity_tolerance_mps2, 0.2 * gravity_mps2_)
             : options_.gravity_tolerance_mps2;
  std::ostringstream why;
  if (std::abs(accel_mean.norm() - gravity_mps2_) > gravity_tolerance) {
    why << "IMU initialisation: mean specific force " << accel_mean.norm()
        << " m/s^2 differs from gravity " << gravity_mps2_ << " m/s^2 by more than "
        << gravity_tolerance << " (wrong units? set imu.accel_scale)";
    message_ = why.str();
    status_ = Status::kFailed;
    return;
  }
  if (moving) {
    why << "the vehicle moves during the IMU initialisation (" << options_.duration_s
        << " s): accel spread " << accel_std << " m/s^2 (rest: at most "
        << options_.max_accel_std_mps2 << "), gyro spread " << gyro_std
        << " rad/s (at most " << options_.max_gyro_std_radps << "), mean rate "
        << gyro_mean.norm() << " rad/s (at most " << options_.max_gyro_mean_radps << ")";
    message_ = why.str();
  }
  // At rest the accelerometer reads −Rᵀ g = Rᵀ (0, 0, |g|): R rotates the reading onto +z.
  state_ = NavState{};
  state_.t_ns = samples_.back().t_ns;
  state_.R_map_imu = lie::SO3d(
      Eigen::Quaterniond::FromTwoVectors(accel_mean.normalized(), Eigen::Vector3d::UnitZ()));
  state_.gyro_bias = moving ? Eigen::Vector3d::Zero() : gyro_mean;
  state_.gravity_map = Eigen::Vector3d(0.0, 0.0, -gravity_mps2_);
  status_ = moving ? Status::kMoving : Status::kDone;
}

}  // namespace hylo::estimation
