// Point-to-plane refinement of the ICP initializer's result (icp_initializer_internal.h).
#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "icp_initializer_internal.h"

namespace hylo::registration::internal {
namespace {

constexpr double kCauchyScaleM = 0.1;
constexpr double kStepEpsilonM = 1e-4;
constexpr double kStepEpsilonRad = 1e-5;

}  // namespace

Eigen::Isometry3d PlaneRefine(const PointCloud& source, const NeighborSearch& map,
                              const Eigen::Isometry3d& T_map_source, double max_nn_m,
                              int max_iterations) {
  Eigen::Isometry3d T = T_map_source;
  std::vector<Neighbor> neighbors;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    // Residual r = n . q + d of q = T p; a left perturbation q' = Exp(dtheta) q + dt gives
    // dr/d(dtheta, dt) = [(q x n)^T, n^T].
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
    int pairs = 0;
    for (const Eigen::Vector3f& p : source) {
      if (!p.allFinite()) continue;
      const Eigen::Vector3d q = T * p.cast<double>();
      double nn_sq = 0.0;
      Plane plane;
      if (!LocalPlane(map, q, max_nn_m, &neighbors, &nn_sq, &plane)) continue;
      const double r = plane.Distance(q);
      const double w = 1.0 / (1.0 + (r * r) / (kCauchyScaleM * kCauchyScaleM));
      Eigen::Matrix<double, 6, 1> J;
      J << q.cross(plane.normal), plane.normal;
      H += w * J * J.transpose();
      g += w * r * J;
      ++pairs;
    }
    if (pairs < 6) break;
    // A little damping keeps a direction no plane constrains (a corridor) where it is.
    H.diagonal().array() += 1e-6 * H.trace() / 6.0;
    const Eigen::Matrix<double, 6, 1> step = H.ldlt().solve(-g);
    if (!step.allFinite()) break;
    const Eigen::Vector3d dtheta = step.head<3>();
    const double angle = dtheta.norm();
    const Eigen::Matrix3d dR = angle > 0.0
                                   ? Eigen::AngleAxisd(angle, dtheta / angle).toRotationMatrix()
                                   : Eigen::Matrix3d::Identity();
    T.linear() = dR * T.linear();
    T.translation() = dR * T.translation() + step.tail<3>();
    if (step.tail<3>().norm() < kStepEpsilonM && angle < kStepEpsilonRad) break;
  }
  return T;
}

}  // namespace hylo::registration::internal
