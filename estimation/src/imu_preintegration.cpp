#include "hylo/estimation/imu_preintegration.h"

#include "hylo/common/time.h"

namespace hylo::estimation {

using lie::SO3d;

namespace {
// Blocks of the 15-entry residual / error state, nav_state.h order.
constexpr int kTheta = 0, kP = 3, kV = 6, kBg = 9, kBa = 12;
}  // namespace

ImuPreintegration::ImuPreintegration(const Eigen::Vector3d& gyro_bias,
                                     const Eigen::Vector3d& accel_bias, const ImuNoise& noise)
    : noise_(noise), gyro_bias_(gyro_bias), accel_bias_(accel_bias) {}

void ImuPreintegration::Integrate(const ImuInterval& in) {
  const double dt = in.dt_s;
  if (dt <= 0.0) return;
  const Eigen::Vector3d omega_dt = (in.gyro_imu - gyro_bias_) * dt;
  const Eigen::Vector3d accel = in.accel_imu - accel_bias_;
  const Matrix3 dR = delta_R_.Matrix();
  const Matrix3 dR_a_hat = dR * SO3d::Hat(accel);
  const SO3d step = SO3d::Exp(omega_dt);
  const Matrix3 step_T = step.Inverse().Matrix();
  const Matrix3 Jr = SO3d::RightJacobian(omega_dt);

  // Noise propagation (Eq. 62-63), error state [δθ, δp, δv]. Discrete white noise of a
  // continuous density σ has variance σ²/dt and enters multiplied by dt, so the added
  // covariance is B·diag(σ² dt)·Bᵀ with B the noise-to-state map below without the dt.
  Matrix9 A = Matrix9::Identity();
  A.block<3, 3>(kTheta, kTheta) = step_T;
  A.block<3, 3>(kP, kTheta) = -0.5 * dR_a_hat * dt * dt;
  A.block<3, 3>(kP, kV) = Matrix3::Identity() * dt;
  A.block<3, 3>(kV, kTheta) = -dR_a_hat * dt;
  Eigen::Matrix<double, 9, 6> B = Eigen::Matrix<double, 9, 6>::Zero();
  B.block<3, 3>(kTheta, 0) = Jr;
  B.block<3, 3>(kP, 3) = 0.5 * dR * dt;
  B.block<3, 3>(kV, 3) = dR;
  Eigen::Matrix<double, 6, 1> q;
  // Inside an IMU gap, an unknown constant error of variance σ² over dt adds σ² dt² (its
  // integral is the error times dt), through the same map B.
  const double sg = in.gap_gyro_sigma_radps, sa = in.gap_accel_sigma_mps2;
  q << Eigen::Vector3d::Constant(noise_.gyro_noise_density * noise_.gyro_noise_density * dt +
                                 sg * sg * dt * dt),
      Eigen::Vector3d::Constant(noise_.accel_noise_density * noise_.accel_noise_density * dt +
                                sa * sa * dt * dt);
  covariance_ = A * covariance_ * A.transpose() + B * q.asDiagonal() * B.transpose();

  // Bias Jacobians (Appendix B), using the values before this step on the right-hand sides.
  dp_dba_ += dv_dba_ * dt - 0.5 * dR * dt * dt;
  dp_dbg_ += dv_dbg_ * dt - 0.5 * dR_a_hat * dR_dbg_ * dt * dt;
  dv_dba_ -= dR * dt;
  dv_dbg_ -= dR_a_hat * dR_dbg_ * dt;
  dR_dbg_ = step_T * dR_dbg_ - Jr * dt;

  // Deltas (Eq. 35): position first, it uses the velocity before the step.
  delta_p_ += delta_v_ * dt + 0.5 * (dR * accel) * dt * dt;
  delta_v_ += dR * accel * dt;
  delta_R_ = delta_R_ * step;
  dt_s_ += dt;
}

ImuCovariance ImuPreintegration::ResidualCovariance() const {
  ImuCovariance C = ImuCovariance::Zero();
  C.topLeftCorner<9, 9>() = covariance_;
  const double bg = noise_.gyro_bias_random_walk, ba = noise_.accel_bias_random_walk;
  C.block<3, 3>(kBg, kBg).diagonal().setConstant(bg * bg * dt_s_);
  C.block<3, 3>(kBa, kBa).diagonal().setConstant(ba * ba * dt_s_);
  return C;
}

NavState ImuPreintegration::Predict(const NavState& x_i, const Eigen::Vector3d& g) const {
  const Eigen::Vector3d dbg = x_i.gyro_bias - gyro_bias_;
  const Eigen::Vector3d dba = x_i.accel_bias - accel_bias_;
  const SO3d dR = delta_R_ * SO3d::Exp(dR_dbg_ * dbg);
  const Eigen::Vector3d dv = delta_v_ + dv_dbg_ * dbg + dv_dba_ * dba;
  const Eigen::Vector3d dp = delta_p_ + dp_dbg_ * dbg + dp_dba_ * dba;
  NavState x_j = x_i;
  x_j.t_ns = x_i.t_ns + SecondsToNanos(dt_s_);
  x_j.R_map_imu = x_i.R_map_imu * dR;
  x_j.v_map_imu = x_i.v_map_imu + g * dt_s_ + x_i.R_map_imu * dv;
  x_j.p_map_imu = x_i.p_map_imu + x_i.v_map_imu * dt_s_ + 0.5 * g * dt_s_ * dt_s_ +
                  x_i.R_map_imu * dp;
  return x_j;
}

ImuResidual ImuPreintegration::Evaluate(const NavState& x_i, const NavState& x_j,
                                        const Eigen::Vector3d& g, ImuJacobian* jacobian_i,
                                        ImuJacobian* jacobian_j,
                                        Eigen::Matrix<double, 15, 3>* jacobian_gravity) const {
  const double dt = dt_s_;
  const Eigen::Vector3d dbg = x_i.gyro_bias - gyro_bias_;
  const Eigen::Vector3d dba = x_i.accel_bias - accel_bias_;
  const Eigen::Vector3d phi_bias = dR_dbg_ * dbg;
  const SO3d dR_corrected = delta_R_ * SO3d::Exp(phi_bias);  // Eq. (44)
  const Eigen::Vector3d dv = delta_v_ + dv_dbg_ * dbg + dv_dba_ * dba;
  const Eigen::Vector3d dp = delta_p_ + dp_dbg_ * dbg + dp_dba_ * dba;
  const Matrix3 Ri_T = x_i.R_map_imu.Inverse().Matrix();
  const Eigen::Vector3d dp_world =
      x_j.p_map_imu - x_i.p_map_imu - x_i.v_map_imu * dt - 0.5 * g * dt * dt;
  const Eigen::Vector3d dv_world = x_j.v_map_imu - x_i.v_map_imu - g * dt;

  ImuResidual r;
  const SO3d E = dR_corrected.Inverse() * x_i.R_map_imu.Inverse() * x_j.R_map_imu;
  const Eigen::Vector3d r_theta = E.Log();
  r.segment<3>(kTheta) = r_theta;
  r.segment<3>(kP) = Ri_T * dp_world - dp;
  r.segment<3>(kV) = Ri_T * dv_world - dv;
  r.segment<3>(kBg) = x_j.gyro_bias - x_i.gyro_bias;
  r.segment<3>(kBa) = x_j.accel_bias - x_i.accel_bias;

  const Matrix3 Jr_inv = SO3d::RightJacobianInverse(r_theta);
  const Matrix3 I = Matrix3::Identity();
  if (jacobian_i != nullptr) {
    ImuJacobian& J = *jacobian_i;
    J.setZero();
    // R_i·Exp(δ): E becomes E·Exp(−R_jᵀR_i δ); (R_i Exp(δ))ᵀ w ≈ R_iᵀ w + [R_iᵀ w]^ δ.
    J.block<3, 3>(kTheta, kTheta) =
        -Jr_inv * (x_j.R_map_imu.Inverse() * x_i.R_map_imu).Matrix();
    // Exp(φ_b + J δ) ≈ Exp(φ_b)·Exp(Jr(φ_b) J δ), moved through Eᵀ = Exp(−r_θ).
    J.block<3, 3>(kTheta, kBg) =
        -Jr_inv * SO3d::Exp(-r_theta).Matrix() * SO3d::RightJacobian(phi_bias) * dR_dbg_;
    J.block<3, 3>(kP, kTheta) = SO3d::Hat(Ri_T * dp_world);
    J.block<3, 3>(kP, kP) = -Ri_T;
    J.block<3, 3>(kP, kV) = -Ri_T * dt;
    J.block<3, 3>(kP, kBg) = -dp_dbg_;
    J.block<3, 3>(kP, kBa) = -dp_dba_;
    J.block<3, 3>(kV, kTheta) = SO3d::Hat(Ri_T * dv_world);
    J.block<3, 3>(kV, kV) = -Ri_T;
    J.block<3, 3>(kV, kBg) = -dv_dbg_;
    J.block<3, 3>(kV, kBa) = -dv_dba_;
    J.block<3, 3>(kBg, kBg) = -I;
    J.block<3, 3>(kBa, kBa) = -I;
  }
  if (jacobian_j != nullptr) {
    ImuJacobian& J = *jacobian_j;
    J.setZero();
    J.block<3, 3>(kTheta, kTheta) = Jr_inv;
    J.block<3, 3>(kP, kP) = Ri_T;
    J.block<3, 3>(kV, kV) = Ri_T;
    J.block<3, 3>(kBg, kBg) = I;
    J.block<3, 3>(kBa, kBa) = I;
  }
  if (jacobian_gravity != nullptr) {
    jacobian_gravity->setZero();
    jacobian_gravity->block<3, 3>(kP, 0) = -0.5 * Ri_T * dt * dt;
    jacobian_gravity->block<3, 3>(kV, 0) = -Ri_T * dt;
  }
  return r;
}

}  // namespace hylo::estimation
