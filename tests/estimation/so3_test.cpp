#include "hylo/lie/so3.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "lie_test_util.h"

// Property tests of SO3: every check compares against something computed independently (a
// long-double power series, central differences, or the matrix algebra), at the identity, at
// θ = 1e-9, on both sides of the series/closed-form switches, at generic angles and near π.

namespace hylo::lie {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat3L = Eigen::Matrix<long double, 3, 3>;
using namespace lie::testing;  // kPi, kAngles, RandomUnit, MaxAbs, Numeric/JetJacobian

// A few rotation vectors of each angle in kAngles, along random axes (fixed seed).
std::vector<Vec3> TestVectors() {
  std::mt19937 rng(42);
  std::vector<Vec3> out;
  for (double angle : kAngles) {
    for (int k = 0; k < 3; ++k) out.push_back(angle * RandomUnit(&rng));
  }
  return out;
}

Mat3L HatL(const Vec3& v) { return SO3d::Hat(v).cast<long double>(); }

// Σ_k coeff(k) Φ^k in long double; coeff(k) = 1/k! gives Exp, 1/(k+1)! gives Jl.
template <class Coeff>
Mat3 MatrixSeries(const Vec3& phi, Coeff coeff) {
  const Mat3L P = HatL(phi);
  Mat3L power = Mat3L::Identity();
  Mat3L sum = Mat3L::Zero();
  for (int k = 0; k < 80; ++k) {
    sum += coeff(k) * power;
    power = power * P;
  }
  return sum.cast<double>();
}

long double Factorial(int n) { return 1.0L / InvFactorial(n); }
long double Sign(int k) { return k % 2 == 0 ? 1.0L : -1.0L; }
// |B_2n| for n = 1..9 (Bernoulli numbers), for the cot series of InverseJacobianCoeff.
const long double kAbsBernoulli[] = {1.0L / 6,  1.0L / 30,     1.0L / 42,
                                     1.0L / 30, 5.0L / 66,     691.0L / 2730,
                                     7.0L / 6,  3617.0L / 510, 43867.0L / 798};

// Checks one coefficient function f(u = θ²) of lie_common.h, in value and in Jet derivative
// d/du (what Ceres sees), against its power series Σ term(k) u^k summed in long double, on
// both sides of its switch angle. A wrong series term, or a branch that disagrees with the
// closed form in value or slope, fails. Below the switch the series must agree to rounding;
// above it the closed form cancels, so it gets `closed_rel_tol` (values) and 1e3 times that
// for slopes (one more power of 1/θ² lost, θ ≈ 0.1, with margin).
template <class F, class Term>
void CheckCoefficient(const char* name, const F& f, const Term& term, double switch_theta_sq,
                      double closed_rel_tol) {
  using Jet1 = ceres::Jet<double, 1>;
  for (double theta : {0.0, 1e-9, 1e-3, 0.0099, 0.0101, 0.05, 0.0999, 0.1001, 0.2}) {
    const long double u = static_cast<long double>(theta) * theta;
    long double value = 0.0L, slope = 0.0L, u_pow = 1.0L;
    for (int k = 0; k < 8; ++k) {
      value += term(k) * u_pow;
      slope += (k + 1) * term(k + 1) * u_pow;
      u_pow *= u;
    }
    const double u_d = theta * theta;
    const bool series_branch = u_d < switch_theta_sq;
    const double tol = series_branch ? 1e-15 : closed_rel_tol;
    EXPECT_LE(std::abs(f(u_d) - value), tol * std::abs(value)) << name << " θ=" << theta;
    const double slope_tol = series_branch ? 1e-13 : 1e3 * closed_rel_tol;
    const Jet1 jet = f(Jet1(u_d, 0));
    EXPECT_LE(std::abs(jet.v[0] - slope), slope_tol * std::abs(slope)) << name << " θ=" << theta;
  }
}

// Closed-form tolerances at θ ≈ 0.1: a numerator that cancels like θ^m keeps a relative
// rounding error ~ε·(scale)/θ^m: none for sin(θ/2)/θ and cos(θ/2), m = 2 for C, D and (after
// the half-angle rewrite) E, and m = 4 for the SE3 third coefficient (2θ − 3 sin θ + θ cos θ).
TEST(LieCoefficients, MatchTheirPowerSeriesInValueAndDerivative) {
  const double small = detail::kTaylorThetaSqSmall, large = detail::kTaylorThetaSqLarge;
  CheckCoefficient(
      "SinHalfOverTheta", [](const auto& u) { return detail::SinHalfOverTheta(u); },
      [](int k) { return Sign(k) / (Factorial(2 * k + 1) * std::pow(2.0L, 2 * k + 1)); }, small,
      1e-15);
  CheckCoefficient(
      "CosHalf", [](const auto& u) { return detail::CosHalf(u); },
      [](int k) { return Sign(k) / (Factorial(2 * k) * std::pow(4.0L, k)); }, small, 1e-15);
  CheckCoefficient(
      "ThetaMinusSinOverThetaCubed",
      [](const auto& u) { return detail::ThetaMinusSinOverThetaCubed(u); },
      [](int k) { return Sign(k) / Factorial(2 * k + 3); }, large, 1e-12);
  CheckCoefficient(
      "InverseJacobianCoeff", [](const auto& u) { return detail::InverseJacobianCoeff(u); },
      [](int k) { return kAbsBernoulli[k] / Factorial(2 * k + 2); }, large, 1e-12);
  CheckCoefficient(
      "SE3QCoeff2", [](const auto& u) { return detail::SE3QCoeff2(u); },
      [](int k) { return Sign(k) / Factorial(2 * k + 4); }, large, 1e-12);
  CheckCoefficient(
      "SE3QCoeff3", [](const auto& u) { return detail::SE3QCoeff3(u); },
      [](int k) { return Sign(k) * (k + 1) / Factorial(2 * k + 5); }, large, 1e-9);
}

TEST(SO3, ExpMatchesMatrixExponentialSeries) {
  for (const Vec3& phi : TestVectors()) {
    const Mat3 expected = MatrixSeries(phi, InvFactorial);
    EXPECT_LT(MaxAbs(SO3d::Exp(phi).Matrix() - expected), 2e-15) << phi.transpose();
  }
}

TEST(SO3, LogOfExpGivesBackTheVectorToRelativePrecision) {
  for (const Vec3& phi : TestVectors()) {
    const Vec3 back = SO3d::Exp(phi).Log();
    // Relative: at θ = 1e-9 an acos-of-trace Log would be wrong by O(1) relative.
    EXPECT_LE((back - phi).norm(), 1e-13 * phi.norm() + 1e-300) << phi.transpose();
  }
}

TEST(SO3, ExpOfLogGivesBackTheRotation) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const SO3d R(Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)));
    const Vec3 phi = R.Log();
    EXPECT_LE(phi.norm(), kPi + 1e-15);
    // A few ulps of entries up to 1: how many depends on the compiler's contraction of a*b+c.
    EXPECT_LT(MaxAbs(SO3d::Exp(phi).Matrix() - R.Matrix()), 1e-14);
  }
}

TEST(SO3, LogNearPiFromAMatrixKeepsTheAxis) {
  std::mt19937 rng(11);
  for (double angle : {kPi, kPi - 1e-9, kPi - 1e-6}) {
    for (int i = 0; i < 20; ++i) {
      const Vec3 axis = RandomUnit(&rng);
      const Mat3 R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
      const Vec3 phi = SO3d::FromMatrix(R).Log();
      EXPECT_NEAR(phi.norm(), angle, 1e-14);
      EXPECT_LT(phi.normalized().cross(axis).norm(), 1e-14);  // ±axis: both valid at π
      EXPECT_LT(MaxAbs(SO3d::Exp(phi).Matrix() - R), 1e-15);
    }
  }
}

TEST(SO3, HatIsTheCrossProductAndVeeItsInverse) {
  std::mt19937 rng(3);
  for (int i = 0; i < 20; ++i) {
    const Vec3 a = 2.0 * RandomUnit(&rng), b = RandomUnit(&rng);
    EXPECT_LT((SO3d::Hat(a) * b - a.cross(b)).norm(), 1e-15);
    EXPECT_EQ(SO3d::Vee(SO3d::Hat(a)), a);
  }
}

TEST(SO3, CompositionInverseAndActionAgreeWithMatrices) {
  const std::vector<Vec3> phis = TestVectors();
  const Vec3 p(0.3, -1.2, 2.5);
  for (size_t i = 0; i + 1 < phis.size(); ++i) {
    const SO3d A = SO3d::Exp(phis[i]), B = SO3d::Exp(phis[i + 1]);
    EXPECT_LT(MaxAbs((A * B).Matrix() - A.Matrix() * B.Matrix()), 1e-15);
    EXPECT_LT(MaxAbs((A * A.Inverse()).Matrix() - Mat3::Identity()), 1e-15);
    EXPECT_LT((A * p - A.Matrix() * p).norm(), 1e-14);
    EXPECT_NEAR(A.unit_quaternion().norm(), 1.0, 1e-15);
  }
}

TEST(SO3, AdjointConjugatesTangentVectors) {
  const std::vector<Vec3> phis = TestVectors();
  for (size_t i = 0; i + 1 < phis.size(); ++i) {
    const SO3d X = SO3d::Exp(phis[i]);
    const Vec3 xi = phis[i + 1];
    const Mat3 conj = X.Matrix() * SO3d::Hat(xi) * X.Inverse().Matrix();
    EXPECT_LT((X.Adjoint() * xi - SO3d::Vee(conj)).norm(), 1e-14);
    const SO3d lhs = SO3d::Exp(X.Adjoint() * xi);
    const SO3d rhs = X * SO3d::Exp(xi) * X.Inverse();
    EXPECT_LT(MaxAbs(lhs.Matrix() - rhs.Matrix()), 1e-14);
  }
}

TEST(SO3, LeftJacobianMatchesItsSeries) {
  for (const Vec3& phi : TestVectors()) {
    const Mat3 expected = MatrixSeries(phi, [](int k) { return InvFactorial(k + 1); });
    EXPECT_LT(MaxAbs(SO3d::LeftJacobian(phi) - expected), 2e-15) << phi.transpose();
  }
}

TEST(SO3, InverseJacobiansAreInverses) {
  for (const Vec3& phi : TestVectors()) {
    EXPECT_LT(MaxAbs(SO3d::RightJacobianInverse(phi) * SO3d::RightJacobian(phi) - Mat3::Identity()),
              1e-14);
    EXPECT_LT(MaxAbs(SO3d::LeftJacobianInverse(phi) * SO3d::LeftJacobian(phi) - Mat3::Identity()),
              1e-14);
  }
}

// Each Jacobian against central differences of its defining relation (header comment).
// h = 1e-7 keeps Exp(φ)·Exp(h e) below π when |φ| = π − 1e-6, so Log does not wrap.
TEST(SO3, JacobiansMatchCentralDifferencesOfTheirDefinitions) {
  ExpectJacobiansMatchCentralDifferences<SO3d>(TestVectors(), /*h=*/1e-7, /*tolerance=*/1e-7);
}

TEST(SO3, PlusAndMinusAreInverse) {
  const std::vector<Vec3> phis = TestVectors();
  for (size_t i = 0; i + 1 < phis.size(); ++i) {
    const SO3d x = SO3d::Exp(phis[i]);
    const Vec3 delta = phis[i + 1];  // |δ| < π, so Minus recovers it exactly
    EXPECT_LE((Minus(Plus(x, delta), x) - delta).norm(), 1e-13 * delta.norm() + 1e-300);
    EXPECT_LT(MaxAbs((x * SO3d::Exp(delta)).Matrix() - Plus(x, delta).Matrix()), 1e-15);
  }
}

// Jets: derivatives through the small-angle branches must be finite and exact.
TEST(SO3, JetDerivativeOfPerturbedActionIsMinusRTimesHatP) {
  const Vec3 p(0.4, -2.0, 1.3);
  for (const Vec3& phi : TestVectors()) {
    const SO3d R = SO3d::Exp(phi);
    const Mat3 J = JetJacobian<3>(
        [&](const auto& d) {
          using JetT = typename std::decay_t<decltype(d)>::Scalar;
          const SO3<JetT> Rj = R.cast<JetT>();
          return (Plus(Rj, d) * p.cast<JetT>()).eval();
        },
        Vec3::Zero());
    const Mat3 expected = -R.Matrix() * SO3d::Hat(p);
    EXPECT_LT(MaxAbs(J - expected), 1e-14) << phi.transpose();
  }
}

TEST(SO3, JetDerivativeOfExpActionUsesTheRightJacobian) {
  const Vec3 p(0.4, -2.0, 1.3);
  for (const Vec3& phi : TestVectors()) {
    const Mat3 J = JetJacobian<3>(
        [&](const auto& x) {
          using JetT = typename std::decay_t<decltype(x)>::Scalar;
          return (SO3<JetT>::Exp(x) * p.cast<JetT>()).eval();
        },
        phi);
    // d/dφ Exp(φ)p = −Exp(φ) p^ Jr(φ), from Exp(φ + δ) ≈ Exp(φ) Exp(Jr δ).
    const Mat3 expected = -SO3d::Exp(phi).Matrix() * SO3d::Hat(p) * SO3d::RightJacobian(phi);
    EXPECT_LT(MaxAbs(J - expected), 1e-13) << phi.transpose();
  }
}

TEST(SO3, JetDerivativeOfLogIsTheRightJacobianInverse) {
  for (const Vec3& phi : TestVectors()) {
    const SO3d R = SO3d::Exp(phi);
    const Mat3 J = JetJacobian<3>(
        [&](const auto& d) {
          using JetT = typename std::decay_t<decltype(d)>::Scalar;
          return Minus(Plus(R.cast<JetT>(), d), SO3<JetT>());
        },
        Vec3::Zero());
    EXPECT_LT(MaxAbs(J - SO3d::RightJacobianInverse(phi)), 1e-12) << phi.transpose();
  }
}

}  // namespace
}  // namespace hylo::lie
