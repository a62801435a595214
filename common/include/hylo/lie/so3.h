#pragma once
// SO3<T>: 3D rotations, templated on the scalar so the same code runs with double and with
// ceres::Jet (autodiff).
//
// Storage: a unit quaternion. Four numbers instead of nine, composition is 16 multiplies
// instead of 27, re-normalising after every product is one sqrt (a matrix would need an SVD
// to get back onto SO(3)), Log near θ = π reads the axis straight from the vector part through
// atan2 (no ill-conditioned acos of the trace), and the Ceres smoother can keep the same four
// numbers as its parameter block. Matrix() builds the 3×3 matrix on demand.
//
// Conventions (ARCHITECTURE.md): right perturbation R ⊞ δ = R · Exp(δ) (see Plus/Minus in
// lie_common.h). Jacobians follow Barfoot, "State Estimation for Robotics" (2017), §7.1.5:
//   Exp(φ + δ) ≈ Exp(φ) · Exp(Jr(φ) δ)           Log(Exp(φ) · Exp(δ)) ≈ φ + Jr⁻¹(φ) δ
//   Exp(φ + δ) ≈ Exp(Jl(φ) δ) · Exp(φ)           Log(Exp(δ) · Exp(φ)) ≈ φ + Jl⁻¹(φ) δ
// with Jr(φ) = Jl(−φ). The inverse Jacobians are defined for |φ| < 2π.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hylo/common/check.h"
#include "hylo/lie/lie_common.h"

namespace hylo::lie {

template <typename T>
class SO3 {
 public:
  using Scalar = T;
  using Tangent = Eigen::Matrix<T, 3, 1>;  ///< rotation vector φ = θ·axis, rad
  using Point = Eigen::Matrix<T, 3, 1>;
  using Matrix3 = Eigen::Matrix<T, 3, 3>;
  using Quaternion = Eigen::Quaternion<T>;
  static constexpr int kDof = 3;

  /// The identity rotation.
  SO3() : q_(Quaternion::Identity()) {}

  /// From any non-zero quaternion; it is normalised (q and −q give the same rotation).
  explicit SO3(const Quaternion& q) : q_(q) { Normalize(); }

  /// From a rotation matrix (orthonormal up to rounding). Eigen's conversion picks the largest
  /// of w, x, y, z to divide by (Shepperd's method), so it is robust near θ = π.
  static SO3 FromMatrix(const Matrix3& R) { return SO3(Quaternion(R)); }

  static SO3 Identity() { return SO3(); }

  /// exp: rotation vector → rotation. Exact quaternion [cos(θ/2), sin(θ/2)/θ · φ].
  static SO3 Exp(const Tangent& phi) {
    const T theta_sq = phi.squaredNorm();
    const Tangent vec = detail::SinHalfOverTheta(theta_sq) * phi;
    return SO3(Quaternion(detail::CosHalf(theta_sq), vec.x(), vec.y(), vec.z()));
  }

  /// log: rotation → rotation vector with |φ| ∈ [0, π]. At exactly θ = π both ±φ are valid;
  /// the sign then follows the stored quaternion.
  Tangent Log() const {
    // q and −q are the same rotation; choosing w ≥ 0 puts θ = 2·atan2(|v|, w) in [0, π].
    const bool flip = q_.w() < T(0.0);
    const T w = flip ? T(-q_.w()) : q_.w();
    const Tangent v = flip ? Tangent(-q_.vec()) : Tangent(q_.vec());
    return detail::QuaternionLogScale(w, v.squaredNorm()) * v;
  }

  /// φ^: the skew-symmetric matrix with Hat(a)·b = a × b.
  static Matrix3 Hat(const Tangent& phi) {
    Matrix3 m;
    m << T(0.0), -phi.z(), phi.y(),  //
        phi.z(), T(0.0), -phi.x(),   //
        -phi.y(), phi.x(), T(0.0);
    return m;
  }

  /// Inverse of Hat (reads the lower-triangular entries; no symmetry check).
  static Tangent Vee(const Matrix3& m) { return Tangent(m(2, 1), m(0, 2), m(1, 0)); }

  /// Jl(φ) = I + (1 − cos θ)/θ² Φ + (θ − sin θ)/θ³ Φ², Φ = φ^ (Barfoot Eq. 7.37).
  static Matrix3 LeftJacobian(const Tangent& phi) {
    const T theta_sq = phi.squaredNorm();
    const Matrix3 Phi = Hat(phi);
    return Matrix3::Identity() + detail::OneMinusCosOverThetaSq(theta_sq) * Phi +
           detail::ThetaMinusSinOverThetaCubed(theta_sq) * (Phi * Phi);
  }

  /// Jr(φ) = Jl(−φ).
  static Matrix3 RightJacobian(const Tangent& phi) { return LeftJacobian(Tangent(-phi)); }

  /// Jl⁻¹(φ) = I − ½Φ + (1 − (θ/2)cot(θ/2))/θ² Φ² (Barfoot Eq. 7.40), for θ < 2π.
  static Matrix3 LeftJacobianInverse(const Tangent& phi) {
    const Matrix3 Phi = Hat(phi);
    return Matrix3::Identity() - T(0.5) * Phi +
           detail::InverseJacobianCoeff(phi.squaredNorm()) * (Phi * Phi);
  }

  /// Jr⁻¹(φ) = Jl⁻¹(−φ).
  static Matrix3 RightJacobianInverse(const Tangent& phi) {
    return LeftJacobianInverse(Tangent(-phi));
  }

  /// The 3×3 rotation matrix.
  Matrix3 Matrix() const { return q_.toRotationMatrix(); }

  /// Adjoint: R · Exp(φ) · R⁻¹ = Exp(Ad(R) φ), and Ad(R) = R for SO(3).
  Matrix3 Adjoint() const { return Matrix(); }

  SO3 Inverse() const { return SO3(q_.conjugate(), NoNormalize{}); }

  /// Composition. Re-normalises, so long chains (IMU integration) do not drift off SO(3).
  SO3 operator*(const SO3& other) const { return SO3(q_ * other.q_); }
  SO3& operator*=(const SO3& other) { return *this = *this * other; }

  /// Rotates a point (or vector): R · p.
  Point operator*(const Point& p) const { return q_ * p; }

  /// Unit quaternion with Eigen's (x, y, z, w) coefficient order in memory.
  const Quaternion& unit_quaternion() const { return q_; }

  /// The same rotation with another scalar type (e.g. double → ceres::Jet).
  template <typename U>
  SO3<U> cast() const {
    return SO3<U>(q_.template cast<U>());
  }

 private:
  struct NoNormalize {};
  SO3(const Quaternion& unit_q, NoNormalize) : q_(unit_q) {}

  void Normalize() {
    const T norm_sq = q_.squaredNorm();
    HYLO_CHECK(norm_sq > T(1e-20), "SO3 from a (near) zero quaternion");
    using std::sqrt;
    q_.coeffs() /= sqrt(norm_sq);
  }

  Quaternion q_;
};

using SO3d = SO3<double>;

}  // namespace hylo::lie
