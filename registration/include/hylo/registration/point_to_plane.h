#pragma once
// The project's one point-to-plane solver, composed of three parts (as small_gicp composes a
// registration from a factor, a kernel and a reduction):
//  - the factor: a point of the body (the frame the pose moves) against a map plane,
//    r = nᵀ(R p + t) + d, linearised for the right perturbation R·Exp(δθ), t + δt that every
//    estimator of the project uses (NavState, SO3Manifold);
//  - a robust kernel (robust_kernel.h), as IRLS weights;
//  - the reduction of the linearised residuals into normal equations, in point order, so a
//    sum is the same on every run.
// The ICP initializer's refinement and the wide-basin registration step a 6-DoF pose with it
// (SolveStep, ApplyStep); the IESKF reduces its 12-column system (pose and extrinsic) with the
// same Reduce and adds its prior; the sliding window evaluates the same factor inside Ceres.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <cstddef>

#include "hylo/lie/se3.h"
#include "hylo/registration/plane_matcher.h"
#include "hylo/registration/robust_kernel.h"

namespace hylo::registration {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// ∂r/∂[δθ; δt] of r = nᵀ(R p + t) + d at body point `p_body`: R·Exp(δθ)·p ≈ R p − R [p]^ δθ,
/// so ∂r/∂δθ = −nᵀ R [p]^ = (p × Rᵀn)ᵀ, and ∂r/∂δt = nᵀ.
inline Vector6 PointToPlaneJacobian(const Eigen::Matrix3d& R_map_body,
                                    const Eigen::Vector3d& p_body, const Plane& plane) {
  Vector6 J;
  J.head<3>() = p_body.cross(R_map_body.transpose() * plane.normal);
  J.tail<3>() = plane.normal;
  return J;
}

/// One point's part of a problem, as a problem hands it to Reduce.
template <int N>
struct LinearizedResidual {
  bool matched = false;  ///< a plane was found for the point (its residual is in `r`)
  bool used = false;     ///< ... and it passed the problem's gate: it enters the sums
  double r = 0.0;        ///< signed point-to-plane distance, m
  Eigen::Matrix<double, N, 1> J = Eigen::Matrix<double, N, 1>::Zero();  ///< ∂r/∂δ, when used
};

/// Σ w J Jᵀ and Σ w r J over the used residuals, and what the problem's points gave.
template <int N>
struct NormalEquations {
  Eigen::Matrix<double, N, N> JtJ = Eigen::Matrix<double, N, N>::Zero();
  Eigen::Matrix<double, N, 1> Jtr = Eigen::Matrix<double, N, 1>::Zero();
  std::size_t matched = 0;  ///< points with a plane
  std::size_t used = 0;     ///< ... in the sums
  std::size_t inliers = 0;  ///< matched points within the caller's inlier distance of their plane
};

/// Reduces `linearize(i)` (a LinearizedResidual<N>) over i = 0 .. n-1, weighted by `kernel`;
/// `inlier_m`: matched residuals with |r| below it are counted as inliers (0: none).
template <int N, class Linearize>
NormalEquations<N> Reduce(std::size_t n, const Linearize& linearize, const RobustKernel& kernel,
                          double inlier_m = 0.0) {
  NormalEquations<N> eq;
  const bool weighted = kernel.type != RobustKernel::Type::kNone;
  for (std::size_t i = 0; i < n; ++i) {
    const LinearizedResidual<N> l = linearize(i);
    if (!l.matched) continue;
    ++eq.matched;
    if (std::abs(l.r) < inlier_m) ++eq.inliers;
    if (!l.used) continue;
    ++eq.used;
    if (weighted) {
      const double w = kernel.Weight(l.r);
      eq.JtJ.noalias() += w * l.J * l.J.transpose();
      eq.Jtr.noalias() += (w * l.r) * l.J;
    } else {
      eq.JtJ.noalias() += l.J * l.J.transpose();
      eq.Jtr.noalias() += l.r * l.J;
    }
  }
  return eq;
}

/// The Gauss-Newton step δ = −(JᵀJ + λI)⁻¹ Jᵀr, λ = ridge · max diag(JᵀJ) + 1e-9: the small
/// ridge keeps a direction no plane constrains (a corridor) at zero step. False when the step
/// is not finite.
inline bool SolveStep(const NormalEquations<6>& eq, Vector6* step, double ridge = 1e-6) {
  Matrix6 A = eq.JtJ;
  A.diagonal().array() += ridge * A.diagonal().maxCoeff() + 1e-9;
  *step = -A.ldlt().solve(eq.Jtr);
  return step->allFinite();
}

/// T ⊞ δ = (R·Exp(δθ), t + δt), δ = [δθ; δt].
inline lie::SE3d ApplyStep(const lie::SE3d& T, const Vector6& step) {
  return lie::SE3d(T.so3() * lie::SO3d::Exp(step.head<3>()), T.translation() + step.tail<3>());
}

}  // namespace hylo::registration
