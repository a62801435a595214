// IESKF: construction, IMU buffering, propagation and prediction (the update is in
// ieskf_update.cpp).
#include "hylo/estimation/ieskf.h"

#include <algorithm>

#include "hylo/common/check.h"
#include "hylo/common/time.h"
#include "hylo/estimation/imu_propagation.h"

namespace hylo::estimation {

using namespace state_index;  // NOLINT: index names only

Ieskf::Ieskf(const Options& options) : options_(options) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("invalid options: " + why);
}

StateCovariance Ieskf::InitialCovariance(const IeskfOptions& o) {
  StateCovariance P = StateCovariance::Zero();
  const auto set = [&P](int index, double sigma) {
    P.block<3, 3>(index, index).diagonal().setConstant(sigma * sigma);
  };
  set(kRotation, o.init_rotation_sigma_rad);
  set(kPosition, 1e-4);  // the map frame is defined by the first pose
  set(kVelocity, o.init_velocity_sigma_mps);
  set(kGyroBias, o.init_gyro_bias_sigma_radps);
  set(kAccelBias, o.init_accel_bias_sigma_mps2);
  set(kGravity, o.init_gravity_sigma_mps2);
  set(kExtrinsicRotation, o.init_extrinsic_rotation_sigma_rad);
  set(kExtrinsicTranslation, o.init_extrinsic_translation_sigma_m);
  return P;
}

void Ieskf::Initialize(const NavState& state, const StateCovariance& covariance) {
  state_ = state;
  P_ = 0.5 * (covariance + covariance.transpose());
  omega_cv_imu_.setZero();
  initialized_ = true;
  TrimImu(state.t_ns);
}

void Ieskf::AddImu(const ImuSample& sample) {
  if (!options_.use_imu) return;
  if (!imu_.empty() && sample.t_ns <= imu_.back().t_ns) return;  // the queue sorts; ignore
  imu_.push_back(sample);
}

void Ieskf::TrimImu(int64_t t_ns) {
  // Keep the last sample at or before t_ns: the next interval interpolates from it.
  auto first_after = std::upper_bound(imu_.begin(), imu_.end(), t_ns,
                                      [](int64_t t, const ImuSample& s) { return t < s.t_ns; });
  if (first_after != imu_.begin()) imu_.erase(imu_.begin(), first_after - 1);
}

NavState Ieskf::PredictAt(int64_t t_ns) const {
  return PredictNominal(state_, imu_, options_.use_imu, omega_cv_imu_, t_ns);
}

void Ieskf::Propagate(int64_t t_ns) {
  if (t_ns <= state_.t_ns) return;
  if (!options_.use_imu) {
    PropagateConstantVelocity(t_ns);
    return;
  }
  for (const ImuInterval& in : MakeIntervals(imu_, state_.t_ns, t_ns)) {
    const StateCovariance F = PropagationJacobian(state_, in);
    P_ = F * P_ * F.transpose() + PropagationNoise(options_.imu_noise, in);
    state_ = PropagateNominal(state_, in);
  }
  state_.t_ns = t_ns;
  TrimImu(t_ns);
}

void Ieskf::PropagateConstantVelocity(int64_t t_ns) {
  // Constant velocity (KISS-ICP-like): pose extrapolated with the last velocity, pose
  // uncertainty grows as a random walk; velocities are re-estimated after each update.
  const double dt = NanosToSeconds(t_ns - state_.t_ns);
  const Eigen::Vector3d omega_dt = omega_cv_imu_ * dt;
  StateCovariance F = StateCovariance::Identity();
  F.block<3, 3>(kRotation, kRotation) = lie::SO3d::Exp(-omega_dt).Matrix();
  P_ = F * P_ * F.transpose();
  const IeskfOptions& o = options_.ieskf;
  P_.block<3, 3>(kRotation, kRotation).diagonal().array() +=
      o.cv_rotation_noise * o.cv_rotation_noise * dt;
  P_.block<3, 3>(kPosition, kPosition).diagonal().array() +=
      o.cv_translation_noise * o.cv_translation_noise * dt;
  state_.R_map_imu = state_.R_map_imu * lie::SO3d::Exp(omega_dt);
  state_.p_map_imu += state_.v_map_imu * dt;
  state_.t_ns = t_ns;
}

}  // namespace hylo::estimation
