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
  /// > 0 when the interval lies in a gap of the IMU stream, its measurement interpolated
  /// across missing samples (or, past the last sample, the recent mean): the spread (1 sigma)
  /// of what the missing samples would have read about it, taken as an unknown constant error
  /// over the gap, which the propagation and the preintegration add as uncertainty
  /// (δθ = δω dt, δv = δa dt, δp = ½ δa dt² over this interval; MakeIntervals scales the
  /// spread so that the intervals of one gap add up to the whole gap's error), so that the
  /// lidar, not the guess, decides the state through and after a dropout.
  double gap_accel_sigma_mps2 = 0.0;  ///< m/s²
  double gap_gyro_sigma_radps = 0.0;  ///< rad/s
};

/// How MakeIntervals treats an IMU gap (ImuBuffer fills it in from the recent signal).
struct ImuGapModel {
  int64_t gap_ns = 0;             ///< consecutive samples farther apart bound a gap, ns (> 0)
  double accel_sigma_mps2 = 0.0;  ///< spread of the recent specific force, m/s²
  double gyro_sigma_radps = 0.0;  ///< spread of the recent angular rate, rad/s
  /// The recent mean signal: what the IMU is taken to read after its last sample (rather than
  /// that one sample held, which may be a bump).
  Eigen::Vector3d accel_mean_imu = Eigen::Vector3d::Zero();  ///< m/s²
  Eigen::Vector3d gyro_mean_imu = Eigen::Vector3d::Zero();   ///< rad/s
};

/// Nominal state after `interval` (t_ns advanced by dt).
NavState PropagateNominal(const NavState& x, const ImuInterval& interval);

/// F = ∂(x' ⊟ x̂')/∂(x ⊟ x̂) at x (24×24).
StateCovariance PropagationJacobian(const NavState& x, const ImuInterval& interval);

/// F P Fᵀ for a propagation Jacobian F, by its 3×3 blocks: F is the identity but for about
/// nine blocks, so the zero blocks are skipped and the identity ones copy (a fifth of the
/// dense product's work; it is paid per IMU sample, and after a lidar gap for every sample of
/// the gap on one scan). Equal to the dense product up to the order of summation.
StateCovariance PropagateCovariance(const StateCovariance& F, const StateCovariance& P);

/// Discrete process noise added over `interval` (white noise and bias random walks, and the
/// gap error of an interval inside an IMU gap).
StateCovariance PropagationNoise(const ImuNoise& noise, const ImuInterval& interval);

/// The measurement of `samples` (sorted by time) at `t_ns`, linearly interpolated; held
/// constant outside the samples. `samples` must not be empty.
ImuSample InterpolateImu(const std::vector<ImuSample>& samples, int64_t t_ns);

/// Splits [t0_ns, t1_ns] at the sample stamps inside it; each interval's measurement is the
/// mean of the interpolated measurements at its two ends (trapezoidal rule). With `gap`, an
/// interval whose nearest samples on either side lie farther apart than gap->gap_ns (or that
/// lies that far past the last sample) carries the gap's spreads, and times after the last
/// sample read the gap's mean signal.
std::vector<ImuInterval> MakeIntervals(const std::vector<ImuSample>& samples, int64_t t0_ns,
                                       int64_t t1_ns, const ImuGapModel* gap = nullptr);

/// The nominal state `x` carried to `t_ns` (Estimator::PredictAt of every back-end): through
/// the buffered `imu` samples (MakeIntervals with `gap`), or without IMU at constant velocity
/// (`v_map_imu` and the body rate `omega_cv_imu`, rad/s). Times at or before x.t_ns return x.
NavState PredictNominal(const NavState& x, const std::vector<ImuSample>& imu, bool use_imu,
                        const Eigen::Vector3d& omega_cv_imu, int64_t t_ns,
                        const ImuGapModel* gap = nullptr);

/// PredictNominal at each of `times_ns` (ascending), bit for bit, in one walk over the samples:
/// each time continues from the state at the last sample before it, where the intervals of
/// MakeIntervals split anyway.
std::vector<NavState> PredictNominalAlong(const NavState& x, const std::vector<ImuSample>& imu,
                                          bool use_imu, const Eigen::Vector3d& omega_cv_imu,
                                          const std::vector<int64_t>& times_ns,
                                          const ImuGapModel* gap = nullptr);

}  // namespace hylo::estimation
