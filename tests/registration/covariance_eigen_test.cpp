// The plane fit's eigen decomposition against Eigen's iterative solver, on the neighbourhoods a
// fit meets: flat patches of 5 and 12 points at any orientation and thickness, lines, blobs,
// exactly coplanar points and far-off coordinates.
#include "hylo/registration/covariance_eigen.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <utility>

namespace hylo::registration {
namespace {

// The covariance of `n` points spread by `sigma` (m) along three random orthogonal axes.
Eigen::Matrix3d Neighbourhood(std::mt19937* rng, int n, const Eigen::Vector3d& sigma,
                              const Eigen::Vector3d& centre) {
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::Matrix3d axes =
      Eigen::Quaterniond(g(*rng), g(*rng), g(*rng), g(*rng)).normalized().toRotationMatrix();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    // A map point (float), relative to the first one, as FitPlane accumulates.
    const Eigen::Vector3f point =
        (centre + axes * Eigen::Vector3d(sigma.x() * g(*rng), sigma.y() * g(*rng),
                                         sigma.z() * g(*rng)))
            .cast<float>();
    if (k == 0) first = point.cast<double>();
    const Eigen::Vector3d q = point.cast<double>() - first;
    sum += q;
    outer += q * q.transpose();
  }
  const Eigen::Vector3d mean = sum / n;
  return outer / n - mean * mean.transpose();
}

struct Agreement {
  int cases = 0, fast = 0;
  double worst_angle_rad = 0.0, worst_value = 0.0;
  // Eigen's closed form (what plane fits used before) against the same reference.
  double direct_angle_rad = 0.0, direct_value = 0.0;
};

double AngleRad(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized()))));
}

void Compare(const Eigen::Matrix3d& cov, Agreement* agreement) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> reference(cov);  // iterative QL
  Eigen::Vector3d normal, values;
  bool fell_back = true;
  CovarianceEigen(cov, &normal, &values, &fell_back);
  ++agreement->cases;
  if (!fell_back) ++agreement->fast;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> direct;
  direct.computeDirect(cov);
  const Eigen::Vector3d& expected = reference.eigenvalues();
  const double scale = expected(2);
  ASSERT_NEAR(normal.norm(), 1.0, 1e-12);
  const auto worst = [&](double* w, double x) { *w = std::max(*w, x); };
  worst(&agreement->worst_value, (values - expected).cwiseAbs().maxCoeff() / scale);
  worst(&agreement->direct_value,
        (direct.eigenvalues() - expected).cwiseAbs().maxCoeff() / scale);
  // The normal is defined where the smallest eigenvalue stands apart.
  if (expected(1) - expected(0) > 1e-3 * scale) {
    const Eigen::Vector3d truth = reference.eigenvectors().col(0);
    worst(&agreement->worst_angle_rad, AngleRad(normal, truth));
    worst(&agreement->direct_angle_rad, AngleRad(direct.eigenvectors().col(0), truth));
  }
}

TEST(CovarianceEigen, AgreesWithTheIterativeSolverOnEveryKindOfNeighbourhood) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Agreement flat, other;
  for (int k = 0; k < 20000; ++k) {
    const int n = k % 2 == 0 ? 5 : 12;
    const Eigen::Vector3d centre(1e4 * u(rng), 1e4 * u(rng), 100.0 * u(rng));
    // Flat patches: 0.05-1 m wide, 0.1 mm to 5 cm thick.
    const double width = 0.05 + 0.95 * u(rng);
    const Eigen::Vector3d patch(width, width * (0.3 + 0.7 * u(rng)),
                                1e-4 + 0.05 * width * u(rng));
    Compare(Neighbourhood(&rng, n, patch, centre), &flat);
  }
  for (int k = 0; k < 5000; ++k) {
    const int n = k % 2 == 0 ? 5 : 12;
    // Lines, blobs and near-double smallest eigenvalues.
    const double w = 0.5 * u(rng);
    const Eigen::Vector3d kinds[3] = {Eigen::Vector3d(w, 1e-5 * w, 1e-5 * w),
                                      Eigen::Vector3d(w, w, w),
                                      Eigen::Vector3d(w, 0.01 * w, 0.0099 * w)};
    Compare(Neighbourhood(&rng, n, kinds[k % 3], Eigen::Vector3d::Zero()), &other);
  }
  for (const auto& [name, a] : {std::pair<const char*, const Agreement&>{"flat patches", flat},
                                 {"lines and blobs", other}}) {
    std::printf("%s: %d of %d without the fallback; worst normal %.2e rad (closed form %.2e), "
                "worst eigenvalue %.2e of the largest (closed form %.2e)\n",
                name, a.fast, a.cases, a.worst_angle_rad, a.direct_angle_rad, a.worst_value,
                a.direct_value);
  }
  EXPECT_GT(flat.fast, flat.cases * 99 / 100);  // the fast path is the usual one
  EXPECT_LT(flat.worst_angle_rad, 1e-7);
  EXPECT_LT(flat.worst_value, 1e-12);
  // Where lines and blobs leave it, the fallback is the closed form, no worse than before.
  EXPECT_LT(other.worst_angle_rad, std::max(1e-7, other.direct_angle_rad));
  EXPECT_LT(other.worst_value, std::max(1e-12, 1.01 * other.direct_value));
}

TEST(CovarianceEigen, CoplanarPointsAndZeroGiveTheDirectSolution) {
  // Three points span a plane exactly: det = 0, the closed form answers.
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov.topLeftCorner<2, 2>() << 2.0, 0.5, 0.5, 1.0;
  Eigen::Vector3d normal, values;
  bool fell_back = false;
  CovarianceEigen(cov, &normal, &values, &fell_back);
  EXPECT_TRUE(fell_back);
  EXPECT_NEAR(std::abs(normal.z()), 1.0, 1e-12);
  EXPECT_NEAR(values(0), 0.0, 1e-12);
  CovarianceEigen(Eigen::Matrix3d::Zero(), &normal, &values, &fell_back);
  EXPECT_TRUE(fell_back);
  EXPECT_TRUE(normal.allFinite());
  EXPECT_EQ(values, Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace hylo::registration
