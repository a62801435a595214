#pragma once
// SE3<T>: rigid transforms T_a_b = (R, t), mapping points from frame b to frame a:
// p_a = R · p_b + t. Templated on the scalar (double or ceres::Jet).
//
// TANGENT ORDER: ξ = [ρ; φ], translation part ρ first (rows 0–2), rotation φ second (3–5).
// Exp(ξ) = (Exp(φ), Jl(φ) ρ) is the matrix exponential of Hat(ξ) = [φ^ ρ; 0 0]; ρ is not the
// translation itself unless φ = 0. Every 6-vector and 6×6 matrix below uses this order.
//
// Conventions: right perturbation X ⊞ δ = X · Exp(δ) (Plus/Minus in lie_common.h). Jacobians
// follow Barfoot, "State Estimation for Robotics" (2017), §7.1.5, whose SE(3) tangent is also
// [ρ; φ]:
//   Exp(ξ + δ) ≈ Exp(ξ) · Exp(Jr(ξ) δ)            Log(Exp(ξ) · Exp(δ)) ≈ ξ + Jr⁻¹(ξ) δ
//   Exp(ξ + δ) ≈ Exp(Jl(ξ) δ) · Exp(ξ)            Log(Exp(δ) · Exp(ξ)) ≈ ξ + Jl⁻¹(ξ) δ
// with Jr(ξ) = Jl(−ξ); the inverses need |φ| < 2π.

#include <Eigen/Core>

#include "hylo/lie/lie_common.h"
#include "hylo/lie/so3.h"

namespace hylo::lie {

template <typename T>
class SE3 {
 public:
  using Scalar = T;
  using Tangent = Eigen::Matrix<T, 6, 1>;  ///< [ρ (m); φ (rad)]
  using Vector3 = Eigen::Matrix<T, 3, 1>;
  using Point = Eigen::Matrix<T, 3, 1>;
  using Matrix3 = Eigen::Matrix<T, 3, 3>;
  using Matrix4 = Eigen::Matrix<T, 4, 4>;
  using Matrix6 = Eigen::Matrix<T, 6, 6>;
  static constexpr int kDof = 6;

  /// The identity transform.
  SE3() : translation_(Vector3::Zero()) {}
  SE3(const SO3<T>& rotation, const Vector3& translation)
      : rotation_(rotation), translation_(translation) {}
  SE3(const typename SO3<T>::Quaternion& q, const Vector3& translation)
      : rotation_(q), translation_(translation) {}

  /// From a homogeneous 4×4 matrix (the bottom row is ignored).
  static SE3 FromMatrix(const Matrix4& m) {
    return SE3(SO3<T>::FromMatrix(m.template topLeftCorner<3, 3>()),
               m.template topRightCorner<3, 1>());
  }

  static SE3 Identity() { return SE3(); }

  /// exp: [ρ; φ] → (Exp(φ), Jl(φ) ρ) (Barfoot Eq. 7.83).
  static SE3 Exp(const Tangent& xi) {
    const Vector3 rho = xi.template head<3>();
    const Vector3 phi = xi.template tail<3>();
    return SE3(SO3<T>::Exp(phi), SO3<T>::LeftJacobian(phi) * rho);
  }

  /// log: (R, t) → [Jl⁻¹(φ) t; φ] with φ = Log(R), |φ| ≤ π.
  Tangent Log() const {
    const Vector3 phi = rotation_.Log();
    Tangent xi;
    xi << SO3<T>::LeftJacobianInverse(phi) * translation_, phi;
    return xi;
  }

  /// ξ^ = [φ^ ρ; 0 0] (4×4).
  static Matrix4 Hat(const Tangent& xi) {
    Matrix4 m = Matrix4::Zero();
    m.template topLeftCorner<3, 3>() = SO3<T>::Hat(xi.template tail<3>());
    m.template topRightCorner<3, 1>() = xi.template head<3>();
    return m;
  }

  /// Inverse of Hat.
  static Tangent Vee(const Matrix4& m) {
    Tangent xi;
    xi << m.template topRightCorner<3, 1>(), SO3<T>::Vee(m.template topLeftCorner<3, 3>());
    return xi;
  }

  /// ad(ξ) = [φ^ ρ^; 0 φ^], the matrix of the Lie bracket: ad(a)·b = Vee([a^, b^]).
  static Matrix6 SmallAdjoint(const Tangent& xi) {
    const Matrix3 phi_hat = SO3<T>::Hat(xi.template tail<3>());
    Matrix6 m = Matrix6::Zero();
    m.template topLeftCorner<3, 3>() = phi_hat;
    m.template topRightCorner<3, 3>() = SO3<T>::Hat(xi.template head<3>());
    m.template bottomRightCorner<3, 3>() = phi_hat;
    return m;
  }

  /// Jl(ξ) = [Jl(φ) Q(ρ, φ); 0 Jl(φ)] (Barfoot Eqs. 7.85–7.86).
  static Matrix6 LeftJacobian(const Tangent& xi) {
    const Vector3 phi = xi.template tail<3>();
    const Matrix3 jl = SO3<T>::LeftJacobian(phi);
    Matrix6 m = Matrix6::Zero();
    m.template topLeftCorner<3, 3>() = jl;
    m.template topRightCorner<3, 3>() = QMatrix(xi.template head<3>(), phi);
    m.template bottomRightCorner<3, 3>() = jl;
    return m;
  }

  /// Jr(ξ) = Jl(−ξ).
  static Matrix6 RightJacobian(const Tangent& xi) { return LeftJacobian(Tangent(-xi)); }

  /// Jl⁻¹(ξ) = [Jl⁻¹(φ) −Jl⁻¹(φ) Q Jl⁻¹(φ); 0 Jl⁻¹(φ)] (block-triangular inverse).
  static Matrix6 LeftJacobianInverse(const Tangent& xi) {
    const Vector3 phi = xi.template tail<3>();
    const Matrix3 jl_inv = SO3<T>::LeftJacobianInverse(phi);
    Matrix6 m = Matrix6::Zero();
    m.template topLeftCorner<3, 3>() = jl_inv;
    m.template topRightCorner<3, 3>() = -jl_inv * QMatrix(xi.template head<3>(), phi) * jl_inv;
    m.template bottomRightCorner<3, 3>() = jl_inv;
    return m;
  }

  /// Jr⁻¹(ξ) = Jl⁻¹(−ξ).
  static Matrix6 RightJacobianInverse(const Tangent& xi) {
    return LeftJacobianInverse(Tangent(-xi));
  }

  /// Homogeneous 4×4 matrix [R t; 0 1].
  Matrix4 Matrix() const {
    Matrix4 m = Matrix4::Identity();
    m.template topLeftCorner<3, 3>() = rotation_.Matrix();
    m.template topRightCorner<3, 1>() = translation_;
    return m;
  }

  /// Ad(X) = [R t^R; 0 R]: X · Exp(ξ) · X⁻¹ = Exp(Ad(X) ξ).
  Matrix6 Adjoint() const {
    const Matrix3 R = rotation_.Matrix();
    Matrix6 m = Matrix6::Zero();
    m.template topLeftCorner<3, 3>() = R;
    m.template topRightCorner<3, 3>() = SO3<T>::Hat(translation_) * R;
    m.template bottomRightCorner<3, 3>() = R;
    return m;
  }

  SE3 Inverse() const {
    const SO3<T> rotation_inv = rotation_.Inverse();
    return SE3(rotation_inv, -(rotation_inv * translation_));
  }

  /// Composition: (T_a_b * T_b_c) = T_a_c.
  SE3 operator*(const SE3& other) const {
    return SE3(rotation_ * other.rotation_, rotation_ * other.translation_ + translation_);
  }
  SE3& operator*=(const SE3& other) { return *this = *this * other; }

  /// Transforms a point: R · p + t.
  Point operator*(const Point& p) const { return rotation_ * p + translation_; }

  const SO3<T>& so3() const { return rotation_; }
  SO3<T>& so3() { return rotation_; }
  const Vector3& translation() const { return translation_; }
  Vector3& translation() { return translation_; }

  /// The same transform with another scalar type (e.g. double → ceres::Jet).
  template <typename U>
  SE3<U> cast() const {
    return SE3<U>(rotation_.template cast<U>(), translation_.template cast<U>());
  }

 private:
  /// Q(ρ, φ), the coupling block of the SE(3) left Jacobian (Barfoot Eq. 7.86):
  /// ½ρ^ + c1 (φ^ρ^ + ρ^φ^ + φ^ρ^φ^) + c2 (φ^φ^ρ^ + ρ^φ^φ^ − 3φ^ρ^φ^)
  ///     + c3 (φ^ρ^φ^φ^ + φ^φ^ρ^φ^).
  static Matrix3 QMatrix(const Vector3& rho, const Vector3& phi) {
    const T theta_sq = phi.squaredNorm();
    const Matrix3 P = SO3<T>::Hat(phi);
    const Matrix3 V = SO3<T>::Hat(rho);
    const Matrix3 PV = P * V;
    const Matrix3 VP = V * P;
    const Matrix3 PVP = PV * P;
    return T(0.5) * V + detail::ThetaMinusSinOverThetaCubed(theta_sq) * (PV + VP + PVP) +
           detail::SE3QCoeff2(theta_sq) * (P * PV + VP * P - T(3.0) * PVP) +
           detail::SE3QCoeff3(theta_sq) * (PVP * P + P * PVP);
  }

  SO3<T> rotation_;
  Vector3 translation_;
};

using SE3d = SE3<double>;

}  // namespace hylo::lie
