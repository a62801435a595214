#pragma once
// Shared pieces of the Lie group library: the trigonometric coefficient functions used by
// SO3/SE3 (each with a Taylor branch near θ = 0) and the one right-perturbation convention
// of the project, Plus/Minus (ARCHITECTURE.md: R ⊞ δ = R · Exp(δ)).
//
// Every coefficient function takes θ² (never θ) so that the small-angle branch is a polynomial
// in θ² = |φ|²: it needs no sqrt, so it is finite and has the right derivative when the scalar
// is a ceres::Jet evaluated at φ = 0 (d sqrt(x)/dx is infinite at 0). Branches compare only
// the scalar part (ceres::Jet's comparison operators do exactly that), so a Jet takes the same
// branch as its double value. Each series keeps terms up to the one whose omitted successor is
// below double precision at the switching angle.

#include <cmath>

namespace hylo::lie {

/// Right perturbation: x ⊞ δ = x · Exp(δ). Works for SO3<T> and SE3<T>.
template <class Group>
Group Plus(const Group& x, const typename Group::Tangent& delta) {
  return x * Group::Exp(delta);
}

/// Inverse of Plus: y ⊟ x = Log(x⁻¹ · y), so Plus(x, Minus(y, x)) == y.
template <class Group>
typename Group::Tangent Minus(const Group& y, const Group& x) {
  return (x.Inverse() * y).Log();
}

namespace detail {

/// θ² below which the functions without cancellation (sin(θ/2)/θ, cos(θ/2)) use their series;
/// at θ = 1e-2 the first omitted term (θ⁸) is < 1e-16 relative.
constexpr double kTaylorThetaSqSmall = 1e-4;
/// θ² below which the functions whose closed form cancels (e.g. (θ − sin θ)/θ³) use their
/// series. At θ = 0.1 the closed forms keep a relative error ~1e-13, and ~3e-10 for the worst
/// (SE3QCoeff3, ~120ε/θ⁴; it multiplies θ⁴-sized matrices, so absolute errors stay ~1e-18),
/// while the series, up to θ⁸, is exact to ~1e-18, and so are its derivatives (what a Jet
/// sees).
constexpr double kTaylorThetaSqLarge = 1e-2;

/// sin(θ/2)/θ (the vector part of Exp(φ) as a quaternion, divided by |φ|).
template <typename T>
T SinHalfOverTheta(const T& theta_sq) {
  if (theta_sq < T(kTaylorThetaSqSmall)) {
    return T(0.5) +
           theta_sq * (T(-1.0 / 48) + theta_sq * (T(1.0 / 3840) + theta_sq * T(-1.0 / 645120)));
  }
  using std::sin;
  using std::sqrt;
  const T theta = sqrt(theta_sq);
  return sin(T(0.5) * theta) / theta;
}

/// cos(θ/2) (the scalar part of Exp(φ) as a quaternion).
template <typename T>
T CosHalf(const T& theta_sq) {
  if (theta_sq < T(kTaylorThetaSqSmall)) {
    return T(1.0) +
           theta_sq * (T(-1.0 / 8) + theta_sq * (T(1.0 / 384) + theta_sq * T(-1.0 / 46080)));
  }
  using std::cos;
  using std::sqrt;
  return cos(T(0.5) * sqrt(theta_sq));
}

/// (1 − cos θ)/θ², written as 2·(sin(θ/2)/θ)² so that it never cancels.
template <typename T>
T OneMinusCosOverThetaSq(const T& theta_sq) {
  const T s = SinHalfOverTheta(theta_sq);
  return T(2.0) * s * s;
}

/// (θ − sin θ)/θ³.
template <typename T>
T ThetaMinusSinOverThetaCubed(const T& theta_sq) {
  if (theta_sq < T(kTaylorThetaSqLarge)) {
    const T& u = theta_sq;
    return T(1.0 / 6) + u * (T(-1.0 / 120) +
                             u * (T(1.0 / 5040) + u * (T(-1.0 / 362880) + u * T(1.0 / 39916800))));
  }
  using std::sin;
  using std::sqrt;
  const T theta = sqrt(theta_sq);
  return (theta - sin(theta)) / (theta_sq * theta);
}

/// (1 − (θ/2)·cot(θ/2))/θ², the Φ² coefficient of the inverse SO3 Jacobians. Written with the
/// half angle, so it stays accurate up to θ → 2π (it does not divide by sin θ, which would
/// lose digits near θ = π through 1 + cos θ).
template <typename T>
T InverseJacobianCoeff(const T& theta_sq) {
  if (theta_sq < T(kTaylorThetaSqLarge)) {
    const T& u = theta_sq;
    return T(1.0 / 12) + u * (T(1.0 / 720) + u * (T(1.0 / 30240) +
                                                  u * (T(1.0 / 1209600) + u * T(1.0 / 47900160))));
  }
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T half = T(0.5) * sqrt(theta_sq);
  return (T(1.0) - half * cos(half) / sin(half)) / theta_sq;
}

/// (θ² + 2 cos θ − 2)/(2θ⁴), second coefficient of the SE3 Q matrix (Barfoot, "State
/// Estimation for Robotics", Eq. 7.86). The numerator is θ² − 4 sin²(θ/2) =
/// (θ − 2 sin(θ/2))(θ + 2 sin(θ/2)), which cancels only as ε/θ², not ε/θ⁴.
template <typename T>
T SE3QCoeff2(const T& theta_sq) {
  if (theta_sq < T(kTaylorThetaSqLarge)) {
    const T& u = theta_sq;
    return T(1.0 / 24) + u * (T(-1.0 / 720) + u * (T(1.0 / 40320) + u * (T(-1.0 / 3628800) +
                                                                         u * T(1.0 / 479001600))));
  }
  using std::sin;
  using std::sqrt;
  const T theta = sqrt(theta_sq);
  const T two_sin_half = T(2.0) * sin(T(0.5) * theta);
  return (theta - two_sin_half) * (theta + two_sin_half) / (T(2.0) * theta_sq * theta_sq);
}

/// (2θ − 3 sin θ + θ cos θ)/(2θ⁵), third coefficient of the SE3 Q matrix (Barfoot Eq. 7.86).
template <typename T>
T SE3QCoeff3(const T& theta_sq) {
  if (theta_sq < T(kTaylorThetaSqLarge)) {
    const T& u = theta_sq;
    return T(1.0 / 120) +
           u * (T(-1.0 / 2520) +
                u * (T(1.0 / 120960) + u * (T(-1.0 / 9979200) + u * T(1.0 / 1245404160))));
  }
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T theta = sqrt(theta_sq);
  return (T(2.0) * theta - T(3.0) * sin(theta) + theta * cos(theta)) /
         (T(2.0) * theta_sq * theta_sq * theta);
}

/// 2·atan2(n, w)/n for a unit quaternion with w ≥ 0 and n = |vec|, so that Log(q) = this · vec.
/// Near the identity (n small) it uses 2·atan(√x)/(√x·w) with x = n²/w², a series in x; near
/// θ = π (w → 0, n → 1) atan2 stays well conditioned, unlike acos of the trace.
template <typename T>
T QuaternionLogScale(const T& w, const T& n_sq) {
  // n² < 2.5e-5 ⇔ θ ≲ 1e-2; there x ≈ θ²/4 and the omitted x⁴/9 term is < 1e-19.
  if (n_sq < T(2.5e-5)) {
    const T x = n_sq / (w * w);
    return (T(2.0) / w) * (T(1.0) + x * (T(-1.0 / 3) + x * (T(1.0 / 5) + x * T(-1.0 / 7))));
  }
  using std::atan2;
  using std::sqrt;
  const T n = sqrt(n_sq);
  return T(2.0) * atan2(n, w) / n;
}

}  // namespace detail
}  // namespace hylo::lie
