#pragma once
// The smoother's Ceres factors (private to hylo::estimation: Ceres is a private dependency).
// Parameter blocks of one window state: rotation (4, unit quaternion x y z w, SO3Manifold),
// position (3, m, map) and speed_bias (9: v_map m/s, b_g rad/s, b_a m/s²).

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "hylo/estimation/imu_preintegration.h"
#include "hylo/estimation/nav_state.h"
#include "hylo/registration/plane_matcher.h"

namespace hylo::estimation {

/// One window state's parameter blocks.
struct StateBlocks {
  double rotation[4] = {0.0, 0.0, 0.0, 1.0};
  double position[3] = {0.0, 0.0, 0.0};
  double speed_bias[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};

  /// `x` with the blocks' values (time, gravity and extrinsic from `x`).
  NavState ToNavState(const NavState& x) const;
  void FromNavState(const NavState& x);
};

/// A scan point (IMU frame) with its plane in the map and its residual weight.
struct PlaneMatch {
  Eigen::Vector3d point_imu = Eigen::Vector3d::Zero();
  registration::Plane plane;
  double sqrt_weight = 1.0;  ///< 1/σ times the robust (IRLS) weight's square root, 1/m
  uint32_t point_index = 0;  ///< the point's index in its scan
};

/// IMU preintegration factor between states i and j (imu_preintegration.h), whitened by the
/// residual covariance. Blocks: rotation_i, position_i, speed_bias_i, the same for j, and the
/// gravity vector (3, m/s², map), shared by the window as the IESKF estimates it: the static
/// initialisation levels the map on a biased accelerometer, and holding that gravity fixed
/// costs accuracy (measured on simulator session A, with either back-end).
class ImuFactor final : public ceres::SizedCostFunction<15, 4, 3, 9, 4, 3, 9, 3> {
 public:
  /// Keeps a reference to `preintegration`, which must outlive the factor.
  explicit ImuFactor(const ImuPreintegration& preintegration);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const ImuPreintegration& preintegration_;
  ImuCovariance sqrt_information_;  // W with Wᵀ W = Σ⁻¹
};

/// Point-to-plane residuals between two scans a and b of the window: a point q of scan a (its
/// IMU frame) against a plane of scan b's own points (b's IMU frame),
/// r_k = w_k (nᵀ R_bᵀ (R_a q_k + p_a − p_b) + d). Blocks: rotation_a, position_a, rotation_b,
/// position_b. The plane moves with b's pose, so the residual constrains the two poses
/// relative to each other, not a pose against a map.
class ScanPairFactor final : public ceres::CostFunction {
 public:
  /// Keeps a reference to `matches` (point of a, plane of b), which must outlive the factor
  /// (and not change size).
  explicit ScanPairFactor(const std::vector<PlaneMatch>& matches);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const std::vector<PlaneMatch>& matches_;
};

/// Zero velocity at rest (standstill.h): r = v_map / σ. Block: speed_bias (its first three
/// entries are the velocity).
class ZeroVelocityFactor final : public ceres::SizedCostFunction<3, 9> {
 public:
  explicit ZeroVelocityFactor(double velocity_noise_mps)
      : sqrt_information_(1.0 / velocity_noise_mps) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  double sqrt_information_;  // 1/σ, s/m
};

/// No-IMU mode: constant velocity over three consecutive poses a, b, c. The change of the
/// mean linear velocity (map) and of the mean body rate between [a, b] and [b, c], whitened
/// by random walks of the given densities over the mean of the two intervals.
ceres::CostFunction* MakeConstantVelocityFactor(double dt_ab_s, double dt_bc_s,
                                                double translation_noise, double rotation_noise);

}  // namespace hylo::estimation
