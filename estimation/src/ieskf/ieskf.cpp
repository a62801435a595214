// IESKF: construction, propagation and prediction (the update is in ieskf_update.cpp).
#include "hylo/estimation/ieskf/ieskf.h"

#include "hylo/common/time.h"
#include "hylo/estimation/imu_propagation.h"

namespace hylo::estimation {

using namespace state_index;  // NOLINT: index names only

void Ieskf::Initialize(const NavState& state, const StateCovariance& covariance) {
  // Restarts (relocalization, a search, a data gap) pass the filter's own state on: the
  // extrinsic they carry is the estimate, not the configuration.
  if (!initialized_) T_imu_lidar_configured_ = state.T_imu_lidar;
  Restart(state);
  P_ = 0.5 * (covariance + covariance.transpose());
}

OnlineCalibration Ieskf::Calibration() const {
  OnlineCalibration c;
  if (!options_.ieskf.online_extrinsic || !initialized_) return c;
  // The filter perturbs on the right (R ⊞ δ = R·Exp(δ)); the report's correction is on the
  // left (R = Exp(c)·R_configured), so the rotation's covariance is turned by R: c ≈ R·δ.
  const lie::SO3d& R = state_.T_imu_lidar.so3();
  const Eigen::Matrix3d R_m = R.Matrix();
  const Eigen::Matrix3d rotation_covariance =
      R_m * P_.block<3, 3>(kExtrinsicRotation, kExtrinsicRotation) * R_m.transpose();
  c.extrinsic_rotation_estimated = true;
  c.extrinsic_rotation_correction_rad = (R * T_imu_lidar_configured_.so3().Inverse()).Log();
  c.extrinsic_rotation_sigma_rad = rotation_covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  c.extrinsic_translation_estimated = true;
  c.extrinsic_translation_correction_m =
      state_.T_imu_lidar.translation() - T_imu_lidar_configured_.translation();
  c.extrinsic_translation_sigma_m = P_.block<3, 3>(kExtrinsicTranslation, kExtrinsicTranslation)
                                        .diagonal()
                                        .cwiseMax(0.0)
                                        .cwiseSqrt();
  return c;
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
