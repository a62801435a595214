// IESKF: construction, propagation and prediction (the update is in ieskf_update.cpp).
#include "hylo/estimation/ieskf/ieskf.h"

#include "hylo/common/time.h"
#include "hylo/estimation/imu_propagation.h"

namespace hylo::estimation {

using namespace state_index;  // NOLINT: index names only

void Ieskf::Initialize(const NavState& state, const StateCovariance& covariance) {
  Restart(state);
  P_ = 0.5 * (covariance + covariance.transpose());
}

void Ieskf::Propagate(int64_t t_ns) {
  if (t_ns <= state_.t_ns) return;
  if (!imu_options_.enabled) {
    PropagateConstantVelocity(t_ns);
    return;
  }
  for (const ImuInterval& in : imu_.Intervals(state_.t_ns, t_ns)) {
    const StateCovariance F = PropagationJacobian(state_, in);
    P_ = PropagateCovariance(F, P_) + PropagationNoise(imu_options_.noise, in);
    state_ = PropagateNominal(state_, in);
  }
  state_.t_ns = t_ns;
  imu_.DropBefore(t_ns);
}

void Ieskf::PropagateConstantVelocity(int64_t t_ns) {
  // Constant velocity (KISS-ICP-like): pose extrapolated with the last velocity, pose
  // uncertainty grows as a random walk; velocities are re-estimated after each update.
  const double dt = NanosToSeconds(t_ns - state_.t_ns);
  const Eigen::Vector3d omega_dt = constant_velocity_.omega_imu() * dt;
  StateCovariance F = StateCovariance::Identity();
  F.block<3, 3>(kRotation, kRotation) = lie::SO3d::Exp(-omega_dt).Matrix();
  P_ = F * P_ * F.transpose();
  const NoImuOptions& o = options_.no_imu;
  P_.block<3, 3>(kRotation, kRotation).diagonal().array() +=
      o.cv_rotation_noise * o.cv_rotation_noise * dt;
  P_.block<3, 3>(kPosition, kPosition).diagonal().array() +=
      o.cv_translation_noise * o.cv_translation_noise * dt;
  state_.R_map_imu = state_.R_map_imu * lie::SO3d::Exp(omega_dt);
  state_.p_map_imu += state_.v_map_imu * dt;
  state_.t_ns = t_ns;
}

}  // namespace hylo::estimation
