#pragma once
// The eigen decomposition a plane fit needs from a 3×3 covariance of a few neighbours: the
// smallest eigenvalue's eigenvector (the normal) and the three eigenvalues (the spread), found
// without trigonometry. A fit runs once per scan point and association, and Eigen's closed
// form (three trigonometric calls and two kernel extractions) was a tenth of a dense scan's
// registration.

#include <Eigen/Core>

namespace hylo::registration {

/// For a symmetric positive semi-definite `covariance`: the unit eigenvector of its smallest
/// eigenvalue and the eigenvalues in ascending order. The smallest eigenvalue λ₀ is the root
/// of the characteristic polynomial p(λ) = det(C − λI) that Newton's method reaches from 0:
/// left of λ₀, p is positive, decreasing and convex, so each step lands between the last
/// iterate and λ₀ and the iterates climb to it. The other two follow from the trace and the sum
/// of principal minors; the eigenvector is the largest cross product of two rows of C − λ₀I.
/// Where that is ill-conditioned (λ₀ near λ₁, a singular or indefinite matrix, no
/// convergence) the result is Eigen's SelfAdjointEigenSolver::computeDirect, so the answer is
/// always one; `fell_back` (optional) says which.
void CovarianceEigen(const Eigen::Matrix3d& covariance, Eigen::Vector3d* smallest_vector,
                     Eigen::Vector3d* values, bool* fell_back = nullptr);

}  // namespace hylo::registration
