#include "hylo/registration/covariance_eigen.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace hylo::registration {
namespace {

constexpr int kMaxNewtonSteps = 16;
// λ₀ to this fraction of the trace: the normal then errs by ~1e-13 · trace / (λ₁ − λ₀) rad.
constexpr double kStepTolerance = 1e-13;
// The best cross product must keep this fraction of trace² (λ₁ λ₂ for a flat patch); below
// it λ₀ and λ₁ are too close for a normal by cross products.
constexpr double kMinCrossFraction = 1e-8;

void Direct(const Eigen::Matrix3d& covariance, Eigen::Vector3d* smallest_vector,
            Eigen::Vector3d* values) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(covariance);
  *smallest_vector = eig.eigenvectors().col(0).normalized();
  *values = eig.eigenvalues();
}

}  // namespace

void CovarianceEigen(const Eigen::Matrix3d& covariance, Eigen::Vector3d* smallest_vector,
                     Eigen::Vector3d* values, bool* fell_back) {
  if (fell_back != nullptr) *fell_back = true;
  const Eigen::Matrix3d& C = covariance;
  const double a = C(0, 0), b = C(1, 1), c = C(2, 2);
  const double d = C(0, 1), e = C(1, 2), f = C(0, 2);
  const double trace = a + b + c;
  const double minors = a * b + b * c + a * c - d * d - e * e - f * f;
  const double det = a * (b * c - e * e) - d * (d * c - e * f) + f * (d * e - b * f);
  // p(λ) = −λ³ + trace λ² − minors λ + det; p(0) = det > 0 puts 0 left of λ₀.
  if (!(trace > 0.0) || !(det > 0.0) || !std::isfinite(det)) {
    Direct(C, smallest_vector, values);
    return;
  }
  double lambda0 = 0.0;
  bool converged = false;
  for (int step = 0; step < kMaxNewtonSteps && !converged; ++step) {
    const double p = ((trace - lambda0) * lambda0 - minors) * lambda0 + det;
    const double slope = (2.0 * trace - 3.0 * lambda0) * lambda0 - minors;
    if (!(slope < 0.0)) break;
    const double delta = p / slope;
    lambda0 -= delta;
    converged = std::abs(delta) <= kStepTolerance * trace;
  }
  if (!converged) {
    Direct(C, smallest_vector, values);
    return;
  }
  // λ₁ + λ₂ and λ₁ λ₂ from the trace and the minors.
  const double sum = trace - lambda0;
  const double product = minors - lambda0 * sum;
  const double root = std::sqrt(std::max(sum * sum - 4.0 * product, 0.0));
  const Eigen::Vector3d r0(a - lambda0, d, f), r1(d, b - lambda0, e), r2(f, e, c - lambda0);
  const Eigen::Vector3d crosses[3] = {r0.cross(r1), r0.cross(r2), r1.cross(r2)};
  int best = 0;
  for (int k = 1; k < 3; ++k) {
    if (crosses[k].squaredNorm() > crosses[best].squaredNorm()) best = k;
  }
  const double best_norm2 = crosses[best].squaredNorm();
  if (!(best_norm2 > kMinCrossFraction * kMinCrossFraction * trace * trace * trace * trace)) {
    Direct(C, smallest_vector, values);
    return;
  }
  *smallest_vector = crosses[best] / std::sqrt(best_norm2);
  *values = Eigen::Vector3d(lambda0, 0.5 * (sum - root), 0.5 * (sum + root));
  if (fell_back != nullptr) *fell_back = false;
}

}  // namespace hylo::registration
