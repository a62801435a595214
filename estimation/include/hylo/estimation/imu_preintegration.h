#pragma once
// IMU preintegration between two states, on the manifold, with first-order bias correction
// (Forster, Carlone, Dellaert, Scaramuzza, "On-Manifold Preintegration for Real-Time
// Visual-Inertial Odometry", T-RO 2017). The smoother's IMU factor.
//
// Preintegrated measurements over [t_i, t_j] at the linearisation biases b̄ (Eq. 35):
//   ΔR ← ΔR·Exp(ω dt)   Δp ← Δp + Δv dt + ½ ΔR a dt²   Δv ← Δv + ΔR a dt
// with ω = ω_m − b̄_g, a = a_m − b̄_a. The residual between states i and j (Eq. 45) with the
// bias-corrected deltas of Eq. (44):
//   r_θ  = Log((ΔR·Exp(J^R_g δb_g))ᵀ R_iᵀ R_j)
//   r_p  = R_iᵀ (p_j − p_i − v_i Δt − ½ g Δt²) − (Δp + J^p_g δb_g + J^p_a δb_a)
//   r_v  = R_iᵀ (v_j − v_i − g Δt) − (Δv + J^v_g δb_g + J^v_a δb_a)
//   r_bg = b_g,j − b_g,i      r_ba = b_a,j − b_a,i      (bias random walk)
// δb = b_i − b̄. Rows and the 15 Jacobian columns follow nav_state.h: [θ, p, v, b_g, b_a],
// right perturbation R·Exp(δθ), additive elsewhere.

#include <Eigen/Core>

#include "hylo/estimation/imu_options.h"
#include "hylo/estimation/imu_propagation.h"
#include "hylo/estimation/nav_state.h"
#include "hylo/lie/so3.h"

namespace hylo::estimation {

/// Error-state dimension the IMU factor touches (θ, p, v, b_g, b_a).
constexpr int kImuFactorDim = 15;
using ImuResidual = Eigen::Matrix<double, kImuFactorDim, 1>;
using ImuJacobian = Eigen::Matrix<double, kImuFactorDim, kImuFactorDim>;
using ImuCovariance = Eigen::Matrix<double, kImuFactorDim, kImuFactorDim>;

class ImuPreintegration {
 public:
  using Matrix3 = Eigen::Matrix3d;
  using Matrix9 = Eigen::Matrix<double, 9, 9>;

  /// Starts an empty preintegration at the linearisation biases.
  ImuPreintegration(const Eigen::Vector3d& gyro_bias, const Eigen::Vector3d& accel_bias,
                    const ImuNoise& noise);

  /// Adds one interval (mean measurement over dt, as MakeIntervals builds them).
  void Integrate(const ImuInterval& interval);

  double dt_s() const { return dt_s_; }
  const lie::SO3d& delta_R() const { return delta_R_; }
  const Eigen::Vector3d& delta_p() const { return delta_p_; }
  const Eigen::Vector3d& delta_v() const { return delta_v_; }
  const Eigen::Vector3d& gyro_bias() const { return gyro_bias_; }    ///< b̄_g, rad/s
  const Eigen::Vector3d& accel_bias() const { return accel_bias_; }  ///< b̄_a, m/s²
  /// Covariance of the preintegrated [δθ, δp, δv] from the white noise (Eq. 63).
  const Matrix9& covariance() const { return covariance_; }
  /// Covariance of the whole residual: the above plus the bias random walks over dt.
  ImuCovariance ResidualCovariance() const;

  /// State j predicted from state i and gravity by the bias-corrected deltas (biases kept).
  NavState Predict(const NavState& x_i, const Eigen::Vector3d& gravity_map) const;

  /// The residual above; `jacobian_i`, `jacobian_j` (may be null) w.r.t. the 15 error-state
  /// entries of each state, `jacobian_gravity` (may be null) w.r.t. the gravity vector.
  ImuResidual Evaluate(const NavState& x_i, const NavState& x_j,
                       const Eigen::Vector3d& gravity_map, ImuJacobian* jacobian_i,
                       ImuJacobian* jacobian_j,
                       Eigen::Matrix<double, kImuFactorDim, 3>* jacobian_gravity = nullptr) const;

 private:
  ImuNoise noise_;
  Eigen::Vector3d gyro_bias_, accel_bias_;
  double dt_s_ = 0.0;
  lie::SO3d delta_R_;
  Eigen::Vector3d delta_p_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d delta_v_ = Eigen::Vector3d::Zero();
  Matrix9 covariance_ = Matrix9::Zero();
  // Bias Jacobians of the deltas (Appendix B).
  Matrix3 dR_dbg_ = Matrix3::Zero();
  Matrix3 dp_dbg_ = Matrix3::Zero(), dp_dba_ = Matrix3::Zero();
  Matrix3 dv_dbg_ = Matrix3::Zero(), dv_dba_ = Matrix3::Zero();
};

}  // namespace hylo::estimation
