#pragma once
// Helpers shared by the SO3 and SE3 property tests: the test angles, numeric and Jet
// derivatives, and the group-generic check of the four Jacobians against central differences
// of their defining relations (written once, instantiated per group).

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>
#include <vector>

namespace hylo::lie::testing {

constexpr double kPi = 3.14159265358979323846;

// Angles that exercise each branch: 0, tiny, both sides of θ = 1e-2 and θ = 0.1 (the series
// switches in lie_common.h), generic, and just below π.
inline const std::vector<double> kAngles = {0.0,    1e-9, 1e-5, 0.0099, 0.0101,    0.0999,
                                            0.1001, 0.7,  2.0,  3.0,    kPi - 1e-6};

inline Eigen::Vector3d RandomUnit(std::mt19937* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Vector3d(n(*rng), n(*rng), n(*rng)).normalized();
}

inline long double InvFactorial(int k) {
  long double f = 1.0L;
  for (int i = 2; i <= k; ++i) f *= i;
  return 1.0L / f;
}

template <class Derived>
double MaxAbs(const Eigen::MatrixBase<Derived>& m) {
  return m.cwiseAbs().maxCoeff();
}

// Central differences of f: R^N → R^N at x with step h.
template <int N, class F>
Eigen::Matrix<double, N, N> NumericJacobian(const F& f, const Eigen::Matrix<double, N, 1>& x,
                                            double h) {
  using Vec = Eigen::Matrix<double, N, 1>;
  Eigen::Matrix<double, N, N> J;
  for (int j = 0; j < N; ++j) {
    const Vec e = h * Vec::Unit(j);
    J.col(j) = (f(Vec(x + e)) - f(Vec(x - e))) / (2.0 * h);
  }
  return J;
}

// Exact derivative (forward-mode autodiff with ceres::Jet) of f: R^N → R^M at x.
template <int M, class F, class Derived>
Eigen::Matrix<double, M, Derived::RowsAtCompileTime> JetJacobian(
    const F& f, const Eigen::MatrixBase<Derived>& x) {
  constexpr int N = Derived::RowsAtCompileTime;
  using JetN = ceres::Jet<double, N>;
  Eigen::Matrix<JetN, N, 1> xj;
  for (int i = 0; i < N; ++i) xj[i] = JetN(x[i], i);
  const Eigen::Matrix<JetN, M, 1> y = f(xj);
  Eigen::Matrix<double, M, N> out;
  for (int i = 0; i < M; ++i) out.row(i) = y[i].v.transpose();
  return out;
}

// Each Jacobian of `Group` against central differences of its defining relation (see the
// group's header): Log(X⁻¹ Exp(x)) ≈ Jr, Log(Exp(x) X⁻¹) ≈ Jl, Log(X Exp(d)) ≈ Jr⁻¹,
// Log(Exp(d) X) ≈ Jl⁻¹. h must keep |φ| + h below π, so Log does not wrap.
template <class Group>
void ExpectJacobiansMatchCentralDifferences(const std::vector<typename Group::Tangent>& tangents,
                                            double h, double tolerance) {
  using Tangent = typename Group::Tangent;
  constexpr int N = Group::kDof;
  for (const Tangent& t : tangents) {
    const Group X = Group::Exp(t);
    const auto jr = NumericJacobian<N>(
        [&](const Tangent& x) { return (X.Inverse() * Group::Exp(x)).Log(); }, t, h);
    const auto jl = NumericJacobian<N>(
        [&](const Tangent& x) { return (Group::Exp(x) * X.Inverse()).Log(); }, t, h);
    const auto jr_inv = NumericJacobian<N>(
        [&](const Tangent& d) { return (X * Group::Exp(d)).Log(); }, Tangent(Tangent::Zero()), h);
    const auto jl_inv = NumericJacobian<N>(
        [&](const Tangent& d) { return (Group::Exp(d) * X).Log(); }, Tangent(Tangent::Zero()), h);
    EXPECT_LT(MaxAbs(Group::RightJacobian(t) - jr), tolerance) << t.transpose();
    EXPECT_LT(MaxAbs(Group::LeftJacobian(t) - jl), tolerance) << t.transpose();
    EXPECT_LT(MaxAbs(Group::RightJacobianInverse(t) - jr_inv), tolerance) << t.transpose();
    EXPECT_LT(MaxAbs(Group::LeftJacobianInverse(t) - jl_inv), tolerance) << t.transpose();
  }
}

}  // namespace hylo::lie::testing
