// The robust point-to-plane ICP of the robust registration, its quality measure and the
// KISS-ICP model error (the flow that uses them is in robust_registration.cpp).
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <vector>

#include "hylo/estimation/robust_registration.h"

namespace hylo::estimation {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

// Geman-McClure weight ρ'(r²) for scale k: 1 at r = 0, 1/4 at r = k, ~k⁴/r⁴ far out, so a
// residual much larger than the scale pulls (almost) nothing (Black and Rangarajan, IJCV 1996).
double GemanMcClureWeight(double r, double k) {
  const double u = 1.0 + (r * r) / (k * k);
  return 1.0 / (u * u);
}

// Gauss-Newton step [δθ; δt] of the weighted point-to-plane residuals at T, right
// perturbation R·Exp(δθ), t + δt (the NavState convention), and the count of points within
// `inlier_m` of their plane at T. False with fewer than 6 matches.
bool Step(const PointCloud& points_lidar, const lie::SE3d& T,
          const registration::PlaneMatcher& planes, double gate_m, double kernel_m, double inlier_m,
          Vector6* step, std::size_t* matches, std::size_t* inliers) {
  Matrix6 JtJ = Matrix6::Zero();
  Vector6 Jtr = Vector6::Zero();
  const Eigen::Matrix3d R = T.so3().Matrix();
  const Eigen::Vector3d t = T.translation();
  registration::Plane plane;
  *matches = 0;
  *inliers = 0;
  for (const Eigen::Vector3f& pf : points_lidar) {
    const Eigen::Vector3d q = pf.cast<double>();
    const Eigen::Vector3d p = R * q + t;
    if (!planes.Match(p, &plane)) continue;
    const double r = plane.Distance(p);
    if (std::abs(r) < inlier_m) ++*inliers;
    if (std::abs(r) > gate_m) continue;
    Vector6 j;
    j.head<3>() = q.cross(R.transpose() * plane.normal);
    j.tail<3>() = plane.normal;
    const double w = GemanMcClureWeight(r, kernel_m);
    JtJ.noalias() += w * j * j.transpose();
    Jtr.noalias() += w * r * j;
    ++*matches;
  }
  if (*matches < 6) return false;
  // A small ridge keeps a direction the planes do not constrain (a corridor) at zero step.
  JtJ.diagonal().array() += 1e-6 * JtJ.diagonal().maxCoeff() + 1e-9;
  *step = -JtJ.ldlt().solve(Jtr);
  return step->allFinite();
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
    Vector6 step;
    ++result.iterations;
    if (!Step(points_lidar, result.T_map_lidar, planes, settings.gate_m, kernel_m,
              settings.inlier_m, &step, &result.matches, &result.inliers)) {
      break;
    }
    lie::SE3d& T = result.T_map_lidar;
    T = lie::SE3d(T.so3() * lie::SO3d::Exp(step.head<3>()), T.translation() + step.tail<3>());
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
