// The IMU's motion in a scenario (vehicle + vibration + mounting) and the scenario IMU.
#include <cmath>

#include "hylo/common/time.h"
#include "hylo/lie/so3.h"
#include "hylo/sim/scenario_simulator.h"

namespace hylo::sim {
namespace {

// Quintic smoothstep 6u^5 - 15u^4 + 10u^3 of u = (t - t0) / ramp and its time derivatives: 0
// before t0 (the rest stays exact), 1 after the ramp, C2 in between.
struct Fade {
  double value = 0.0, rate = 0.0, accel = 0.0;
};
Fade FadeAt(double t_s, double t0_s, double ramp_s) {
  const double u = (t_s - t0_s) / ramp_s;
  if (u <= 0.0) return {};
  if (u >= 1.0) return {1.0, 0.0, 0.0};
  const double w = 1.0 - u;
  return {u * u * u * (10.0 - 15.0 * u + 6.0 * u * u), 30.0 * u * u * w * w / ramp_s,
          60.0 * u * w * (1.0 - 2.0 * u) / (ramp_s * ramp_s)};
}

// A sum of tones and its first two time derivatives.
void Tones(const std::vector<Vibration::Tone>& tones, double t_s, Eigen::Vector3d* s,
           Eigen::Vector3d* ds, Eigen::Vector3d* dds) {
  s->setZero();
  ds->setZero();
  dds->setZero();
  for (const Vibration::Tone& tone : tones) {
    const double w = 2.0 * M_PI * tone.frequency_hz;
    for (int i = 0; i < 3; ++i) {
      const double phase = w * t_s + tone.phase_rad[i];
      const double a = tone.amplitude[i];
      (*s)[i] += a * std::sin(phase);
      (*ds)[i] += a * w * std::cos(phase);
      (*dds)[i] -= a * w * w * std::sin(phase);
    }
  }
}

}  // namespace

VehicleMotion::VehicleMotion(Trajectory vehicle, const Vibration& vibration,
                             int64_t vibration_start_ns, const Eigen::Matrix3d& R_vehicle_imu)
    : vehicle_(std::move(vehicle)),
      vibration_(vibration),
      vibration_start_s_(NanosToSeconds(vibration_start_ns)),
      R_vehicle_imu_(R_vehicle_imu) {}

KinematicState VehicleMotion::StateAt(int64_t t_ns) const {
  KinematicState x = vehicle_.StateAt(t_ns);
  const double t_s = NanosToSeconds(t_ns);
  const Fade fade = FadeAt(t_s, vibration_start_s_, vibration_.ramp_s);
  if (fade.value > 0.0) {
    Eigen::Vector3d s, ds, dds;
    Tones(vibration_.translation, t_s, &s, &ds, &dds);
    x.position_map += fade.value * s;
    x.velocity_map += fade.rate * s + fade.value * ds;
    x.accel_map += fade.accel * s + 2.0 * fade.rate * ds + fade.value * dds;
    // R = R_vehicle Exp(theta): omega = Exp(theta)^T omega_vehicle + Jr(theta) dtheta/dt.
    Tones(vibration_.rotation, t_s, &s, &ds, &dds);
    const Eigen::Vector3d theta = fade.value * s, theta_rate = fade.rate * s + fade.value * ds;
    const Eigen::Matrix3d R_shake = lie::SO3d::Exp(theta).Matrix();
    x.omega_imu = R_shake.transpose() * x.omega_imu + lie::SO3d::RightJacobian(theta) * theta_rate;
    x.R_map_imu = x.R_map_imu * R_shake;
  }
  x.R_map_imu = x.R_map_imu * R_vehicle_imu_;
  x.omega_imu = R_vehicle_imu_.transpose() * x.omega_imu;
  return x;
}

Eigen::Isometry3d VehicleMotion::PoseAt(int64_t t_ns) const {
  const KinematicState x = StateAt(t_ns);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = x.R_map_imu;
  T.translation() = x.position_map;
  return T;
}

ScenarioImu::ScenarioImu(const ImuGrade& grade, uint64_t seed)
    : grade_(grade), base_(grade.base, Rng::Derive(seed, 0x1e0)), rng_(Rng::Derive(seed, 0x1e1)) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      accel_errors_(r, c) =
          rng_.Gaussian(r == c ? grade.accel_scale_sigma : grade.misalignment_sigma_rad);
      gyro_errors_(r, c) =
          rng_.Gaussian(r == c ? grade.gyro_scale_sigma : grade.misalignment_sigma_rad);
    }
  }
  // The wandering bias starts from its stationary distribution.
  for (int i = 0; i < 3; ++i) {
    accel_wander_[i] = rng_.Gaussian(grade.accel_bias_instability_mps2);
    gyro_wander_[i] = rng_.Gaussian(grade.gyro_bias_instability_radps);
  }
}

ImuSample ScenarioImu::Measure(const KinematicState& state, int64_t t_ns) {
  const ImuSample truth = TrueImuSample(state, grade_.base.gravity_mps2, t_ns);
  ImuSample sample = base_.Measure(state, t_ns);
  sample.accel_imu += accel_errors_ * truth.accel_imu + accel_wander_;
  sample.gyro_imu += gyro_errors_ * truth.gyro_imu + gyro_wander_;
  // First-order Gauss-Markov step with the exact discretisation.
  const double phi = std::exp(-1.0 / (grade_.base.rate_hz * grade_.bias_correlation_s));
  const double kick = std::sqrt(1.0 - phi * phi);
  for (int i = 0; i < 3; ++i) {
    accel_wander_[i] =
        phi * accel_wander_[i] + kick * rng_.Gaussian(grade_.accel_bias_instability_mps2);
    gyro_wander_[i] =
        phi * gyro_wander_[i] + kick * rng_.Gaussian(grade_.gyro_bias_instability_radps);
  }
  return sample;
}

}  // namespace hylo::sim
