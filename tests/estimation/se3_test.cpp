#include "hylo/lie/se3.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "lie_test_util.h"

// Property tests of SE3 (tangent [ρ; φ]): against long-double power series, central
// differences of the defining relations, and the 4×4 matrix algebra, at rotation angles 0,
// 1e-9, on both sides of the series switches, generic, and just below π.

namespace hylo::lie {
namespace {

using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat4 = Eigen::Matrix4d;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using namespace lie::testing;  // kPi, kAngles, RandomUnit, MaxAbs, Numeric/JetJacobian

// Tangent vectors [ρ; φ] with |φ| from kAngles (random axes) and ρ of a few metres.
std::vector<Vec6> TestVectors() {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> length(0.1, 3.0);
  std::vector<Vec6> out;
  for (double angle : kAngles) {
    for (int k = 0; k < 3; ++k) {
      Vec6 xi;
      xi << length(rng) * RandomUnit(&rng), angle * RandomUnit(&rng);
      out.push_back(xi);
    }
  }
  return out;
}

// Σ_k coeff(k) A^k in long double.
template <int N, class Coeff>
Eigen::Matrix<double, N, N> MatrixSeries(const Eigen::Matrix<double, N, N>& A, Coeff coeff) {
  using MatL = Eigen::Matrix<long double, N, N>;
  const MatL P = A.template cast<long double>();
  MatL power = MatL::Identity(), sum = MatL::Zero();
  for (int k = 0; k < 80; ++k) {
    sum += coeff(k) * power;
    power = power * P;
  }
  return sum.template cast<double>();
}

TEST(SE3, ExpMatchesMatrixExponentialSeries) {
  for (const Vec6& xi : TestVectors()) {
    const Mat4 expected = MatrixSeries<4>(SE3d::Hat(xi), InvFactorial);
    EXPECT_LT(MaxAbs(SE3d::Exp(xi).Matrix() - expected), 1e-14) << xi.transpose();
  }
}

TEST(SE3, LogOfExpGivesBackTheVector) {
  for (const Vec6& xi : TestVectors()) {
    const Vec6 back = SE3d::Exp(xi).Log();
    EXPECT_LT((back.head<3>() - xi.head<3>()).norm(), 1e-13 * xi.head<3>().norm());
    EXPECT_LE((back.tail<3>() - xi.tail<3>()).norm(), 1e-13 * xi.tail<3>().norm() + 1e-300);
  }
}

TEST(SE3, ExpOfLogGivesBackTheTransform) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const SE3d X(Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)),
                 Vec3(5.0 * n(rng), 5.0 * n(rng), n(rng)));
    EXPECT_LT(MaxAbs(SE3d::Exp(X.Log()).Matrix() - X.Matrix()), 1e-13);
  }
  // Rotation by exactly π, built from a matrix.
  const Vec3 axis = Vec3(1.0, -2.0, 0.5).normalized();
  Mat4 m = Mat4::Identity();
  m.topLeftCorner<3, 3>() = Eigen::AngleAxisd(kPi, axis).toRotationMatrix();
  m.topRightCorner<3, 1>() = Vec3(2.0, 1.0, -3.0);
  EXPECT_LT(MaxAbs(SE3d::Exp(SE3d::FromMatrix(m).Log()).Matrix() - m), 1e-14);
}

TEST(SE3, HatVeeAndTheLieBracket) {
  const std::vector<Vec6> xis = TestVectors();
  for (size_t i = 0; i + 1 < xis.size(); ++i) {
    const Vec6 &a = xis[i], &b = xis[i + 1];
    EXPECT_EQ(SE3d::Vee(SE3d::Hat(a)), a);
    const Mat4 bracket = SE3d::Hat(a) * SE3d::Hat(b) - SE3d::Hat(b) * SE3d::Hat(a);
    EXPECT_LT((SE3d::SmallAdjoint(a) * b - SE3d::Vee(bracket)).norm(), 1e-14);
  }
}

TEST(SE3, CompositionInverseAndActionAgreeWithMatrices) {
  const std::vector<Vec6> xis = TestVectors();
  const Vec3 p(0.3, -1.2, 2.5);
  for (size_t i = 0; i + 1 < xis.size(); ++i) {
    const SE3d A = SE3d::Exp(xis[i]), B = SE3d::Exp(xis[i + 1]);
    EXPECT_LT(MaxAbs((A * B).Matrix() - A.Matrix() * B.Matrix()), 1e-14);
    EXPECT_LT(MaxAbs((A * A.Inverse()).Matrix() - Mat4::Identity()), 1e-14);
    EXPECT_LT((A * p - (A.Matrix() * p.homogeneous()).head<3>()).norm(), 1e-14);
  }
}

TEST(SE3, AdjointConjugatesTangentVectors) {
  const std::vector<Vec6> xis = TestVectors();
  for (size_t i = 0; i + 1 < xis.size(); ++i) {
    const SE3d X = SE3d::Exp(xis[i]);
    const Vec6 xi = xis[i + 1];
    const Mat4 conj = X.Matrix() * SE3d::Hat(xi) * X.Inverse().Matrix();
    EXPECT_LT((X.Adjoint() * xi - SE3d::Vee(conj)).norm(), 1e-13);
    const SE3d lhs = SE3d::Exp(X.Adjoint() * xi);
    const SE3d rhs = X * SE3d::Exp(xi) * X.Inverse();
    EXPECT_LT(MaxAbs(lhs.Matrix() - rhs.Matrix()), 1e-13);
  }
}

// Jl(ξ) = Σ ad(ξ)^k/(k+1)! (Barfoot Eq. 7.85), summed in long double.
TEST(SE3, LeftJacobianMatchesItsSeries) {
  for (const Vec6& xi : TestVectors()) {
    const Mat6 expected =
        MatrixSeries<6>(SE3d::SmallAdjoint(xi), [](int k) { return InvFactorial(k + 1); });
    EXPECT_LT(MaxAbs(SE3d::LeftJacobian(xi) - expected), 1e-14) << xi.transpose();
  }
}

TEST(SE3, InverseJacobiansAreInverses) {
  for (const Vec6& xi : TestVectors()) {
    EXPECT_LT(MaxAbs(SE3d::RightJacobianInverse(xi) * SE3d::RightJacobian(xi) - Mat6::Identity()),
              1e-13);
    EXPECT_LT(MaxAbs(SE3d::LeftJacobianInverse(xi) * SE3d::LeftJacobian(xi) - Mat6::Identity()),
              1e-13);
  }
}

// Each Jacobian against central differences of its defining relation (header comment).
// h = 1e-7 keeps |φ| + h below π, so Log does not wrap.
TEST(SE3, JacobiansMatchCentralDifferencesOfTheirDefinitions) {
  ExpectJacobiansMatchCentralDifferences<SE3d>(TestVectors(), /*h=*/1e-7, /*tolerance=*/1e-7);
}

TEST(SE3, PlusAndMinusAreInverse) {
  const std::vector<Vec6> xis = TestVectors();
  for (size_t i = 0; i + 1 < xis.size(); ++i) {
    const SE3d x = SE3d::Exp(xis[i]);
    const Vec6 delta = xis[i + 1];  // rotation part below π, so Minus recovers it
    EXPECT_LT((Minus(Plus(x, delta), x) - delta).norm(), 1e-13 * delta.norm());
    const SE3d y = SE3d::Exp(xis[i + 1]);
    EXPECT_LT(MaxAbs(Plus(x, Minus(y, x)).Matrix() - y.Matrix()), 1e-13);
  }
}

// d/dδ (X · Exp(δ) · p) at δ = 0 is [R, −R p^] in the [ρ; φ] order; the Jets go through the
// small-angle branches at exactly δ = 0.
TEST(SE3, JetDerivativeOfPerturbedActionIsRAndMinusRHatP) {
  const Vec3 p(0.4, -2.0, 1.3);
  for (const Vec6& xi : TestVectors()) {
    const SE3d X = SE3d::Exp(xi);
    const Eigen::Matrix<double, 3, 6> J = JetJacobian<3>(
        [&](const auto& d) {
          using JetT = typename std::decay_t<decltype(d)>::Scalar;
          return (Plus(X.cast<JetT>(), d) * p.cast<JetT>()).eval();
        },
        Vec6::Zero());
    Eigen::Matrix<double, 3, 6> expected;
    const Eigen::Matrix3d R = X.so3().Matrix();
    expected << R, -R * SO3d::Hat(p);
    EXPECT_LT(MaxAbs(J - expected), 1e-14) << xi.transpose();
  }
}

TEST(SE3, JetDerivativeOfLogIsTheRightJacobianInverse) {
  for (const Vec6& xi : TestVectors()) {
    const SE3d X = SE3d::Exp(xi);
    const Mat6 J = JetJacobian<6>(
        [&](const auto& d) {
          using JetT = typename std::decay_t<decltype(d)>::Scalar;
          return Minus(Plus(X.cast<JetT>(), d), SE3<JetT>());
        },
        Vec6::Zero());
    EXPECT_LT(MaxAbs(J - SE3d::RightJacobianInverse(xi)), 1e-12) << xi.transpose();
  }
}

// The Jacobian functions themselves instantiate with Jets and agree with the double version
// (to rounding: the Jet arithmetic may associate and contract differently, a few ulps of
// entries near 1).
TEST(SE3, JacobiansInstantiateWithJets) {
  using J6 = ceres::Jet<double, 6>;
  for (const Vec6& xi : TestVectors()) {
    const Eigen::Matrix<J6, 6, 6> jr = SE3<J6>::RightJacobian(xi.cast<J6>());
    const Eigen::Matrix<J6, 6, 6> jr_inv = SE3<J6>::RightJacobianInverse(xi.cast<J6>());
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 6; ++c) {
        EXPECT_NEAR(jr(r, c).a, SE3d::RightJacobian(xi)(r, c), 1e-14);
        EXPECT_NEAR(jr_inv(r, c).a, SE3d::RightJacobianInverse(xi)(r, c), 1e-14);
      }
    }
  }
}

}  // namespace
}  // namespace hylo::lie
