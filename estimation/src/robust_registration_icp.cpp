// The robust point-to-plane ICP of the robust registration, its quality measure and the
// KISS-ICP model error (the flow that uses them is in robust_registration.cpp).
#include <algorithm>
#include <cmath>
#include <vector>

#include "hylo/estimation/robust_registration.h"
#include "hylo/registration/point_to_plane.h"

namespace hylo::estimation {
namespace {

// One Gauss-Newton step [δθ; δt] of the point-to-plane residuals at T (right perturbation,
// the NavState convention), residuals gated at `gate_m` and Geman-McClure weighted at scale
// `kernel_m`; *matches and *inliers (within `inlier_m` of their plane) at T. False with fewer
// than 6 matches.
bool Step(const PointCloud& points_lidar, const lie::SE3d& T,
          const registration::PlaneMatcher& planes, double gate_m, double kernel_m, double inlier_m,
          registration::Vector6* step, std::size_t* matches, std::size_t* inliers) {
  const Eigen::Matrix3d R = T.so3().Matrix();
  const Eigen::Vector3d t = T.translation();
  const auto eq = registration::Reduce<6>(
      points_lidar.size(),
      [&](std::size_t i) {
        registration::LinearizedResidual<6> l;
        const Eigen::Vector3d q = points_lidar[i].cast<double>();
        const Eigen::Vector3d p = R * q + t;
        registration::Plane plane;
        if (!planes.Match(p, &plane)) return l;
        l.matched = true;
        l.r = plane.Distance(p);
        l.used = std::abs(l.r) <= gate_m;
        if (l.used) l.J = registration::PointToPlaneJacobian(R, q, plane);
        return l;
      },
      registration::RobustKernel::GemanMcClure(kernel_m), inlier_m);
  *matches = eq.used;
  *inliers = eq.inliers;
  return eq.used >= 6 && registration::SolveStep(eq, step);
}

}  // namespace

PlaneIcpResult AlignPointToPlane(const PointCloud& points_lidar,
                                 const lie::SE3d& T_start, const registration::PlaneMatcher& planes,
                                 const PlaneIcpSettings& settings) {
  // How far a step moves the points: the translation plus the arc at the subset's median
  // range. A scale has settled when its steps move the points by a small part of the scale.
  std::vector<float> ranges;
  ranges.reserve(points_lidar.size());
  for (const Eigen::Vector3f& p : points_lidar) ranges.push_back(p.norm());
  const auto mid = ranges.begin() + static_cast<std::ptrdiff_t>(ranges.size() / 2);
  std::nth_element(ranges.begin(), mid, ranges.end());
  const double median_range_m = ranges.empty() ? 1.0 : static_cast<double>(*mid);
  PlaneIcpResult result;
  result.T_map_lidar = T_start;
  double kernel_m = std::max(settings.kernel_m, settings.final_kernel_m);
  while (result.iterations < settings.max_iterations) {
    registration::Vector6 step;
    ++result.iterations;
    if (!Step(points_lidar, result.T_map_lidar, planes, settings.gate_m, kernel_m,
              settings.inlier_m, &step, &result.matches, &result.inliers)) {
      break;
    }
    result.T_map_lidar = registration::ApplyStep(result.T_map_lidar, step);
    const double moved_m = step.tail<3>().norm() + median_range_m * step.head<3>().norm();
    if (moved_m > settings.settle_fraction * kernel_m) continue;
    // Settled at this scale: narrow the kernel (coarse to fine) or stop at the finest.
    if (kernel_m <= settings.final_kernel_m) {
      result.converged = true;
      break;
    }
    kernel_m = std::max(0.5 * kernel_m, settings.final_kernel_m);
  }
  return result;
}

NavState WithLidarPose(const NavState& x, const lie::SE3d& T_map_lidar) {
  NavState moved = x;
  const lie::SE3d T_map_imu = T_map_lidar * x.T_imu_lidar.Inverse();
  moved.R_map_imu = T_map_imu.so3();
  moved.p_map_imu = T_map_imu.translation();
  return moved;
}

double ModelDeviation(const lie::SE3d& deviation, double max_range_m) {
  const double angle = deviation.so3().Log().norm();
  return deviation.translation().norm() + 2.0 * max_range_m * std::sin(0.5 * angle);
}

}  // namespace hylo::estimation
