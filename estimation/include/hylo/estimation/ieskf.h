#pragma once
// Iterated error-state Kalman filter on the manifold of NavState: the core of FAST-LIO2
// (Xu et al., "FAST-LIO2: Fast Direct LiDAR-Inertial Odometry", T-RO 2022, Sec. IV).
// Propagation with the IMU (or a constant-velocity model without one), then an iterated
// update with point-to-plane residuals whose gain is computed in the state dimension
// (Eq. 20 of the paper, written here as the equivalent Gauss-Newton normal equations).

#include <Eigen/Core>
#include <vector>

#include "hylo/estimation/estimator.h"

namespace hylo::estimation {

/// Compact Jacobian of one point-to-plane residual: [∂r/∂δθ, ∂r/∂δp, ∂r/∂δθ_il, ∂r/∂δt_il]
/// (the only non-zero blocks of the 24-wide row).
using ResidualJacobian = Eigen::Matrix<double, 1, 12>;

/// r = nᵀ·(R_map_imu·(T_imu_lidar·p_lidar) + p_map_imu) + offset, and its Jacobian.
double PointToPlaneResidual(const NavState& x, const Eigen::Vector3d& point_lidar,
                            const registration::Plane& plane, ResidualJacobian* jacobian);

class Ieskf final : public Estimator {
 public:
  /// Throws hylo::InternalError naming the field when `options` is not valid.
  explicit Ieskf(const Options& options);

  void Initialize(const NavState& state, const StateCovariance& covariance) override;
  void AddImu(const ImuSample& sample) override;
  NavState PredictAt(int64_t t_ns) const override;
  UpdateSummary Update(const DeskewedScan& scan,
                       const registration::PlaneMatcher& planes) override;

  bool initialized() const override { return initialized_; }
  const NavState& state() const override { return state_; }
  StateCovariance Covariance() const override { return P_; }
  PoseCovariance6 PoseCovariance() const override { return PoseBlock(P_); }
  const StateCovariance& covariance() const { return P_; }

  /// The initial covariance built from options.ieskf's init_*_sigma fields.
  static StateCovariance InitialCovariance(const IeskfOptions& options);

 private:
  // Normal equations of the lidar residuals over the compact 12 columns.
  struct LidarSystem {
    Eigen::Matrix<double, 12, 12> HtH = Eigen::Matrix<double, 12, 12>::Zero();
    Eigen::Matrix<double, 12, 1> Htr = Eigen::Matrix<double, 12, 1>::Zero();
    std::size_t matches = 0;
    double sum_sq_residual = 0.0;
  };

  void Propagate(int64_t t_ns);                       // ieskf.cpp
  void PropagateConstantVelocity(int64_t t_ns);       // ieskf.cpp
  void TrimImu(int64_t t_ns);                         // ieskf.cpp
  // ieskf_update.cpp
  void Associate(const NavState& x, const DeskewedScan& scan,
                 const registration::PlaneMatcher& planes);
  LidarSystem BuildLidarSystem(const NavState& x, const DeskewedScan& scan,
                               const registration::PlaneMatcher& planes) const;
  NavState SearchYaw(const NavState& prior, const DeskewedScan& scan,
                     const registration::PlaneMatcher& planes);
  void ReportInformation(const LidarSystem& system, UpdateSummary* summary) const;
  int ActiveDim() const;

  Options options_;
  bool initialized_ = false;
  NavState state_;
  StateCovariance P_ = StateCovariance::Identity();
  std::vector<ImuSample> imu_;              // buffered samples, time order
  Eigen::Vector3d omega_cv_imu_ = Eigen::Vector3d::Zero();  // no-IMU: body rate, rad/s
  std::vector<registration::Plane> planes_;  // per scan point, valid where matched_[i]
  std::vector<char> matched_;
};

}  // namespace hylo::estimation
