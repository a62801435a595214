#pragma once
// One scan's point-to-plane cost in closed form (private to hylo::estimation).
//
// Within a solve a scan's matches are fixed: each point q_k (IMU frame) has its plane (n_k, d_k)
// in the map and its weight w_k. Their cost at a pose (R, p) of the scan,
//   Σ_k (w_k (n_kᵀ (R q_k + p) + d_k))²,
// is a quadratic form xᵀ A x in x = [vec(R); p − c; 1] (13 entries, vec column by column; c a
// fixed centre near the scan that keeps A well scaled), whatever the pose: row k is
// a_k = w_k [vec(n_k q_kᵀ); n_k; n_kᵀ c + d_k]. A factor of 13 residuals r = S x with SᵀS = A
// then carries exactly what one residual per point carried, at a cost that does not grow with
// the points (the idea behind BALM's point clusters, here for scan-to-map planes).
#include <ceres/ceres.h>

#include <Eigen/Core>
#include <vector>

#include "sliding_window_factors.h"

namespace hylo::estimation {

struct ScanPlaneSummary {
  static constexpr int kDim = 13;
  using Matrix = Eigen::Matrix<double, kDim, kDim>;
  using Vector = Eigen::Matrix<double, kDim, 1>;

  /// The summary of `matches` (their current weights) about `centre_map` (m, map).
  static ScanPlaneSummary Of(const std::vector<PlaneMatch>& matches,
                             const Eigen::Vector3d& centre_map);

  /// x = [vec(R); p − c; 1] of the pose (R_map_imu, p_map_imu).
  Vector PoseVector(const Eigen::Matrix3d& R_map_imu, const Eigen::Vector3d& p_map_imu) const;

  Eigen::Vector3d centre_map = Eigen::Vector3d::Zero();
  /// S, with SᵀS = A = Σ_k a_k a_kᵀ (from A's eigen-decomposition, which a cost that is near
  /// zero at the optimum leaves near singular).
  Matrix sqrt_information = Matrix::Zero();
};

/// The point-to-plane factor of one scan: r = S x (ScanPlaneSummary), 13 residuals. Blocks:
/// rotation, position. The robust loss enters as fixed IRLS weights in the summary (set
/// between solver rounds), as it did when each point was a residual of its own.
class ScanPlaneFactor final : public ceres::SizedCostFunction<ScanPlaneSummary::kDim, 4, 3> {
 public:
  explicit ScanPlaneFactor(const ScanPlaneSummary& summary) : summary_(summary) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  ScanPlaneSummary summary_;
};

}  // namespace hylo::estimation
