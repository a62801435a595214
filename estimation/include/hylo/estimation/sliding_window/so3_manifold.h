#pragma once
// ceres::Manifold for rotations stored as our SO3's unit quaternion (Eigen coefficient order
// x, y, z, w), with the project's right perturbation R ⊞ δ = R·Exp(δ) (ARCHITECTURE.md), written
// on lie::SO3 so the filter and the smoother share one convention. Header-only; including it
// requires Ceres (hylo::estimation links Ceres privately; a user of this header links it).
//
// Analytic cost functions compute Jacobians w.r.t. the 3-dof tangent; Ceres wants them w.r.t.
// the 4 ambient numbers and multiplies by PlusJacobian. LiftRotationJacobian gives the
// ambient Jacobian J_t·P⁺ whose product with PlusJacobian P is J_t again (P has orthogonal
// columns of norm ½, so P⁺ = 4 Pᵀ); autodiff cost functions keep working with the same
// manifold because PlusJacobian is the true derivative.

#include <ceres/manifold.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hylo/lie/so3.h"

namespace hylo::estimation {

/// d(q ⊗ Exp(δ))/dδ at δ = 0, 4×3, rows in Eigen order (x, y, z, w).
inline Eigen::Matrix<double, 4, 3> RotationPlusJacobian(const double* q_xyzw) {
  const double x = q_xyzw[0], y = q_xyzw[1], z = q_xyzw[2], w = q_xyzw[3];
  Eigen::Matrix<double, 4, 3> P;
  // q ⊗ (0, δ/2): vector part ½(w δ + v × δ), scalar part −½ v·δ.
  P << w, -z, y,  //
      z, w, -x,   //
      -y, x, w,   //
      -x, -y, -z;
  return 0.5 * P;
}

/// Ambient (…×4, row-major into `ambient`) Jacobian from a tangent one (…×3), see above.
template <int Rows>
void LiftRotationJacobian(const double* q_xyzw, const Eigen::Matrix<double, Rows, 3>& tangent,
                          double* ambient) {
  Eigen::Map<Eigen::Matrix<double, Rows, 4, Eigen::RowMajor>> out(ambient);
  out = tangent * (4.0 * RotationPlusJacobian(q_xyzw).transpose());
}

class SO3Manifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 4; }
  int TangentSize() const override { return 3; }

  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    const lie::SO3d R{Eigen::Quaterniond(x)};
    const Eigen::Vector3d d(delta[0], delta[1], delta[2]);
    Eigen::Map<Eigen::Vector4d> out(x_plus_delta);
    out = lie::Plus(R, d).unit_quaternion().coeffs();
    return true;
  }

  bool PlusJacobian(const double* x, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, 4, 3, Eigen::RowMajor>> out(jacobian);
    out = RotationPlusJacobian(x);
    return true;
  }

  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    const lie::SO3d Y{Eigen::Quaterniond(y)}, X{Eigen::Quaterniond(x)};
    Eigen::Map<Eigen::Vector3d> out(y_minus_x);
    out = lie::Minus(Y, X);
    return true;
  }

  bool MinusJacobian(const double* x, double* jacobian) const override {
    // d(Log(x⁻¹ y))/dy at y = x is the left inverse of PlusJacobian: 4 Pᵀ.
    Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> out(jacobian);
    out = 4.0 * RotationPlusJacobian(x).transpose();
    return true;
  }
};

}  // namespace hylo::estimation
