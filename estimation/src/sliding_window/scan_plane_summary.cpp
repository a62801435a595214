#include "scan_plane_summary.h"

#include <Eigen/Eigenvalues>

#include "hylo/estimation/sliding_window/so3_manifold.h"
#include "hylo/lie/so3.h"

namespace hylo::estimation {

ScanPlaneSummary ScanPlaneSummary::Of(const std::vector<PlaneMatch>& matches,
                                      const Eigen::Vector3d& centre_map) {
  ScanPlaneSummary summary;
  summary.centre_map = centre_map;
  // In point order, on one thread: the sum, hence the solve, is the same for any thread count.
  Matrix A = Matrix::Zero();
  Vector a;
  for (const PlaneMatch& m : matches) {
    const Eigen::Vector3d& n = m.plane.normal;
    for (int j = 0; j < 3; ++j) a.segment<3>(3 * j) = n * m.point_imu(j);  // vec(n qᵀ)
    a.segment<3>(9) = n;
    a(12) = n.dot(centre_map) + m.plane.offset;
    a *= m.sqrt_weight;
    A.selfadjointView<Eigen::Lower>().rankUpdate(a);
  }
  A.triangularView<Eigen::StrictlyUpper>() = A.transpose();
  const Eigen::SelfAdjointEigenSolver<Matrix> eigen(A);
  summary.sqrt_information =
      eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() * eigen.eigenvectors().transpose();
  return summary;
}

ScanPlaneSummary::Vector ScanPlaneSummary::PoseVector(const Eigen::Matrix3d& R_map_imu,
                                                      const Eigen::Vector3d& p_map_imu) const {
  Vector x;
  x.head<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(R_map_imu.data());
  x.segment<3>(9) = p_map_imu - centre_map;
  x(12) = 1.0;
  return x;
}

bool ScanPlaneFactor::Evaluate(double const* const* parameters, double* residuals,
                               double** jacobians) const {
  const Eigen::Matrix3d R = Eigen::Quaterniond(parameters[0]).normalized().toRotationMatrix();
  const Eigen::Map<const Eigen::Vector3d> p(parameters[1]);
  const ScanPlaneSummary::Matrix& S = summary_.sqrt_information;
  Eigen::Map<ScanPlaneSummary::Vector>{residuals} = S * summary_.PoseVector(R, p);
  if (jacobians == nullptr) return true;
  using RowMajor13x3 = Eigen::Matrix<double, ScanPlaneSummary::kDim, 3, Eigen::RowMajor>;
  if (jacobians[0] != nullptr) {
    // R ⊞ δθ = R Exp(δθ): ∂vec(R)/∂δθ_m = vec(R [e_m]×).
    Eigen::Matrix<double, 9, 3> dvec_R;
    for (int m = 0; m < 3; ++m) {
      const Eigen::Matrix3d dR = R * lie::SO3d::Hat(Eigen::Vector3d::Unit(m));
      dvec_R.col(m) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(dR.data());
    }
    const Eigen::Matrix<double, ScanPlaneSummary::kDim, 3> tangent = S.leftCols<9>() * dvec_R;
    LiftRotationJacobian<ScanPlaneSummary::kDim>(parameters[0], tangent, jacobians[0]);
  }
  if (jacobians[1] != nullptr) Eigen::Map<RowMajor13x3>{jacobians[1]} = S.middleCols<3>(9);
  return true;
}

}  // namespace hylo::estimation
