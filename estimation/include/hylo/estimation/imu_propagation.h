#pragma once
// Strapdown propagation of the NavState over one IMU interval and its error-state Jacobians
// (right perturbation, layout of nav_state.h). Shared by the IESKF and by PredictAt; exposed
// so that the analytic Jacobians can be checked numerically.
//
// Model over an interval dt with constant bias-corrected rate ω = ω_m − b_g and specific force
// a = a_m − b_a (Sola, "Quaternion kinematics for the error-state Kalman filter", §5.4):
//   R' = R·Exp(ω dt)   v' = v + (R a + g) dt   p' = p + v dt + ½ (R a + g) dt²

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/estimation/imu_options.h"
#include "hylo/estimation/nav_state.h"

namespace hylo::estimation {

/// One propagation interval: duration and the mean measurement over it.
struct ImuInterval {
  double dt_s = 0.0;
  Eigen::Vector3d gyro_imu = Eigen::Vector3d::Zero();   ///< rad/s
  Eigen::Vector3d accel_imu = Eigen::Vector3d::Zero();  ///< m/s²
};

/// Nominal state after `interval` (t_ns advanced by dt).
NavState PropagateNominal(const NavState& x, const ImuInterval& interval);

/// F = ∂(x' ⊟ x̂')/∂(x ⊟ x̂) at x (24×24).
StateCovariance PropagationJacobian(const NavState& x, const ImuInterval& interval);

/// Discrete process noise added over `interval` (white noise and bias random walks).
StateCovariance PropagationNoise(const ImuNoise& noise, const ImuInterval& interval);

/// The measurement of `samples` (sorted by time) at `t_ns`, linearly interpolated; held
/// constant outside the samples. `samples` must not be empty.
ImuSample InterpolateImu(const std::vector<ImuSample>& samples, int64_t t_ns);

/// Splits [t0_ns, t1_ns] at the sample stamps inside it; each interval's measurement is the
/// mean of the interpolated measurements at its two ends (trapezoidal rule).
std::vector<ImuInterval> MakeIntervals(const std::vector<ImuSample>& samples, int64_t t0_ns,
                                       int64_t t1_ns);

/// The nominal state `x` carried to `t_ns` (Estimator::PredictAt of every back-end): through
/// the buffered `imu` samples, or without IMU at constant velocity (`v_map_imu` and the body
/// rate `omega_cv_imu`, rad/s). Times at or before x.t_ns return x itself.
NavState PredictNominal(const NavState& x, const std::vector<ImuSample>& imu, bool use_imu,
                        const Eigen::Vector3d& omega_cv_imu, int64_t t_ns);

}  // namespace hylo::estimation
