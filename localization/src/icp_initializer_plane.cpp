// Point-to-plane refinement of the ICP initializer's result (icp_initializer_internal.h), on the
// project's point-to-plane solver.
#include <Eigen/Geometry>
#include <vector>

#include "hylo/lie/isometry.h"
#include "hylo/registration/point_to_plane.h"
#include "icp_initializer_internal.h"

namespace hylo::localization::internal {
namespace {

constexpr double kCauchyScaleM = 0.1;
constexpr double kStepEpsilonM = 1e-4;
constexpr double kStepEpsilonRad = 1e-5;

}  // namespace

Eigen::Isometry3d PlaneRefine(const PointCloud& source, const registration::NeighborSearch& map,
                              const Eigen::Isometry3d& T_map_source, double max_nn_m,
                              int max_iterations) {
  lie::SE3d T = lie::FromIsometry(T_map_source);
  const registration::RobustKernel kernel = registration::RobustKernel::Cauchy(kCauchyScaleM);
  std::vector<registration::Neighbor> neighbors;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    const Eigen::Matrix3d R = T.so3().Matrix();
    const Eigen::Vector3d t = T.translation();
    const auto eq = registration::Reduce<6>(
        source.size(),
        [&](std::size_t i) {
          registration::LinearizedResidual<6> l;
          if (!source[i].allFinite()) return l;
          const Eigen::Vector3d p = source[i].cast<double>();
          const Eigen::Vector3d q = R * p + t;
          double nn_sq = 0.0;
          registration::Plane plane;
          if (!LocalPlane(map, q, max_nn_m, &neighbors, &nn_sq, &plane)) return l;
          l.matched = l.used = true;
          l.r = plane.Distance(q);
          l.J = registration::PointToPlaneJacobian(R, p, plane);
          return l;
        },
        kernel);
    registration::Vector6 step;
    if (eq.used < 6 || !registration::SolveStep(eq, &step)) break;
    T = registration::ApplyStep(T, step);
    if (step.tail<3>().norm() < kStepEpsilonM && step.head<3>().norm() < kStepEpsilonRad) break;
  }
  return lie::ToIsometry(T);
}

}  // namespace hylo::localization::internal
