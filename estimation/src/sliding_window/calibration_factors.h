#pragma once
// Factors of the smoother's online calibration (private): the lidar-IMU clock offset and a
// rotation of the extrinsic, estimated as corrections to the configured values.
//
// A scan stamped t (after the configured offset) was in truth taken at t + δt on the IMU's
// clock, and its points, mapped into the IMU frame with the configured extrinsic (q = R_il p +
// t_il), are in truth at q' = Q (q − t_il) + t_il (the extrinsic rotation is Q R_il, its
// translation unchanged). The window's state at t (R, p, v, with ω the gyro rate less its
// bias) moved on by δt to first order places the point at
//   P = R Exp(ω δt) q' + p + v δt,
// and the point-to-plane residual is r = w (nᵀ P + d). Both corrections move every point of
// every scan of the window together; only turns and changes of speed tell them apart from the
// pose, which is why each has a Gaussian prior at the configured value.

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <vector>

#include "sliding_window_factors.h"

namespace hylo::estimation {

/// Which calibration blocks exist, in this order after a scan's state blocks.
struct CalibrationLayout {
  bool time_offset = false;         ///< block of 1: δt, s
  bool extrinsic_rotation = false;  ///< block of 4: Q, unit quaternion (x y z w), SO3Manifold
};

/// The scan-to-map factor with calibration. Blocks: rotation (4), position (3), speed_bias (9),
/// then the layout's blocks: time offset (1), extrinsic rotation (4).
class CalibratedScanPlaneFactor final : public ceres::CostFunction {
 public:
  /// Keeps a reference to `matches` (points in the IMU frame by the configured extrinsic),
  /// which must outlive the factor. `rate_imu`: the body rate less the gyro bias at the scan,
  /// rad/s; `lever_arm_imu`: the configured extrinsic's translation, m.
  CalibratedScanPlaneFactor(const std::vector<PlaneMatch>& matches, CalibrationLayout layout,
                            const Eigen::Vector3d& rate_imu, const Eigen::Vector3d& lever_arm_imu);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const std::vector<PlaneMatch>& matches_;
  CalibrationLayout layout_;
  Eigen::Vector3d rate_imu_;
  Eigen::Vector3d lever_arm_imu_;
};

/// r = (δt − centre) / σ. Block: the time offset (1).
ceres::CostFunction* MakeTimeOffsetPriorFactor(double centre_s, double sigma_s);
/// r = Log(Q_centre⁻¹ Q) / σ. Block: the extrinsic rotation (4).
ceres::CostFunction* MakeRotationPriorFactor(const double* centre_xyzw, double sigma_rad);

}  // namespace hylo::estimation
