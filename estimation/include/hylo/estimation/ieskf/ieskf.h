#pragma once
// Iterated error-state Kalman filter on the manifold of NavState: the core of FAST-LIO2
// (Xu et al., "FAST-LIO2: Fast Direct LiDAR-Inertial Odometry", T-RO 2022, Sec. IV).
// Propagation with the IMU (or a constant-velocity model without one), then an iterated
// update with point-to-plane residuals whose gain is computed in the state dimension
// (Eq. 20 of the paper, written here as the equivalent Gauss-Newton normal equations).
// A filter never revisits a state, so each state is final as soon as it is updated.

#include <Eigen/Core>
#include <vector>

#include "hylo/estimation/backend_base.h"
#include "hylo/lie/se3.h"
#include "hylo/registration/point_to_plane.h"

namespace hylo::estimation {

/// Compact Jacobian of one point-to-plane residual: [∂r/∂δθ, ∂r/∂δp, ∂r/∂δθ_il, ∂r/∂δt_il]
/// (the only non-zero blocks of the 24-wide row).
using ResidualJacobian = Eigen::Matrix<double, 1, 12>;

/// r = nᵀ·(R_map_imu·(T_imu_lidar·p_lidar) + p_map_imu) + offset, and its Jacobian.
double PointToPlaneResidual(const NavState& x, const Eigen::Vector3d& point_lidar,
                            const registration::Plane& plane, ResidualJacobian* jacobian);

class Ieskf final : public BackendBase {
 public:
  /// Throws hylo::InternalError naming the field when `options` or `imu` is not valid.
  Ieskf(const EstimatorOptions& options, const ImuOptions& imu) : BackendBase(options, imu) {}

  void Initialize(const NavState& state, const StateCovariance& covariance) override;
  UpdateSummary Update(const DeskewedScan& scan, const registration::PlaneMatcher& planes) override;
  void CarryForward(int64_t t_ns) override {
    if (initialized_ && imu_options_.enabled) Propagate(t_ns);
  }
  StateCovariance Covariance() const override { return P_; }
  PoseCovariance6 PoseCovariance() const override { return PoseBlock(P_); }
  void Finish() override {}  // every state was final as soon as it was updated
  /// With ieskf.online_extrinsic: the filter's T_imu_lidar against the one it first started
  /// from (the configuration's; later starts carry the estimate on), its sigma from P.
  OnlineCalibration Calibration() const override;

 private:
  // Normal equations of the lidar residuals over the compact 12 columns.
  // The lidar residuals' normal equations over [δθ, δp, δθ_il, δt_il].
  using LidarSystem = registration::NormalEquations<12>;

  void Propagate(int64_t t_ns);                  // ieskf.cpp
  void PropagateConstantVelocity(int64_t t_ns);  // ieskf.cpp
  // ieskf_update.cpp
  void Correct(const DeskewedScan& scan, const registration::PlaneMatcher& planes,
               UpdateSummary* summary);
  void Associate(const NavState& x, const DeskewedScan& scan,
                 const registration::PlaneMatcher& planes);
  LidarSystem BuildLidarSystem(const NavState& x, const DeskewedScan& scan,
                               const registration::PlaneMatcher& planes) const;
  void ReportFit(const NavState& x, const DeskewedScan& scan,
                 const registration::PlaneMatcher& planes, UpdateSummary* summary) const;
  int ActiveDim() const;

  StateCovariance P_ = StateCovariance::Identity();
  lie::SE3d T_imu_lidar_configured_;  // the first Initialize's
  std::vector<registration::Plane> planes_;  // per scan point, valid where matched_[i]
  std::vector<char> matched_;
};

}  // namespace hylo::estimation
