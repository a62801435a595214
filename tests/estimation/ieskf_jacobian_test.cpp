// Every analytic Jacobian of the IESKF against central differences on the manifold (⊞/⊟ of
// nav_state.h): propagation F, the point-to-plane residual row, and the ⊞/⊟ pair itself.
#include <gtest/gtest.h>

#include <random>

#include "hylo/estimation/ieskf/ieskf.h"
#include "hylo/estimation/imu_propagation.h"

namespace hylo::estimation {
namespace {

using namespace state_index;  // NOLINT

NavState RandomState(std::mt19937* rng, double rotation_scale) {
  std::normal_distribution<double> n(0.0, 1.0);
  auto v = [&](double s) -> Eigen::Vector3d {
    return Eigen::Vector3d(n(*rng), n(*rng), n(*rng)) * s;
  };
  NavState x;
  x.R_map_imu = lie::SO3d::Exp(v(rotation_scale));
  x.p_map_imu = v(10.0);
  x.v_map_imu = v(1.0);
  x.gyro_bias = v(0.01);
  x.accel_bias = v(0.1);
  x.gravity_map = Eigen::Vector3d(0, 0, -9.81) + v(0.05);
  x.T_imu_lidar = lie::SE3d(lie::SO3d::Exp(v(0.1)), v(0.3));
  return x;
}

StateVector Delta(int i, double h) {
  StateVector d = StateVector::Zero();
  d(i) = h;
  return d;
}

class JacobianTest : public ::testing::TestWithParam<double> {};

TEST_P(JacobianTest, BoxPlusMinusRoundTrip) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const NavState x = RandomState(&rng, GetParam());
    StateVector d = StateVector::Random() * 0.3;
    const StateVector back = BoxMinus(BoxPlus(x, d), x);
    EXPECT_LT((back - d).norm(), 1e-10);
  }
}

TEST_P(JacobianTest, PropagationJacobianMatchesCentralDifferences) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 10; ++trial) {
    const NavState x = RandomState(&rng, GetParam());
    ImuInterval in;
    in.dt_s = 0.005 * (1 + trial);
    in.gyro_imu = Eigen::Vector3d(0.3, -0.8, 1.2) * (trial % 3);
    in.accel_imu = Eigen::Vector3d(0.5, -1.0, 9.6);
    const StateCovariance F = PropagationJacobian(x, in);
    const NavState y = PropagateNominal(x, in);
    const double h = 1e-6;
    for (int i = 0; i < kDim; ++i) {
      const StateVector plus = BoxMinus(PropagateNominal(BoxPlus(x, Delta(i, h)), in), y);
      const StateVector minus = BoxMinus(PropagateNominal(BoxPlus(x, Delta(i, -h)), in), y);
      const StateVector numeric = (plus - minus) / (2 * h);
      EXPECT_LT((numeric - F.col(i)).norm(), 1e-6) << "column " << i << " trial " << trial;
    }
  }
}

TEST_P(JacobianTest, BlockCovariancePropagationEqualsTheDenseProduct) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 10; ++trial) {
    const NavState x = RandomState(&rng, GetParam());
    ImuInterval in;
    in.dt_s = 0.0025 * (1 + trial);
    in.gyro_imu = Eigen::Vector3d(0.3, -0.8, 1.2) * (trial % 3);
    in.accel_imu = Eigen::Vector3d(0.5, -1.0, 9.6);
    const StateCovariance A = StateCovariance::Random();
    const StateCovariance P = A * A.transpose() + StateCovariance::Identity();
    // The propagation Jacobian, and a matrix with no zero or identity block at all.
    for (const StateCovariance& F : {PropagationJacobian(x, in), StateCovariance(A)}) {
      const StateCovariance dense = F * P * F.transpose();
      const StateCovariance blocks = PropagateCovariance(F, P);
      EXPECT_LT((blocks - dense).norm(), 1e-12 * dense.norm()) << "trial " << trial;
    }
  }
}

TEST_P(JacobianTest, PointToPlaneJacobianMatchesCentralDifferences) {
  std::mt19937 rng(3);
  const int columns[12] = {0, 1, 2, 3, 4, 5, 18, 19, 20, 21, 22, 23};
  for (int trial = 0; trial < 20; ++trial) {
    const NavState x = RandomState(&rng, GetParam());
    registration::Plane plane;
    plane.normal = Eigen::Vector3d::Random().normalized();
    plane.offset = 2.0;
    const Eigen::Vector3d p_lidar = Eigen::Vector3d::Random() * 20.0;
    ResidualJacobian J;
    PointToPlaneResidual(x, p_lidar, plane, &J);
    const double h = 1e-6;
    for (int c = 0; c < 12; ++c) {
      const double rp = PointToPlaneResidual(BoxPlus(x, Delta(columns[c], h)), p_lidar, plane,
                                             nullptr);
      const double rm = PointToPlaneResidual(BoxPlus(x, Delta(columns[c], -h)), p_lidar, plane,
                                             nullptr);
      EXPECT_NEAR((rp - rm) / (2 * h), J(c), 1e-6) << "column " << columns[c];
    }
    // Every other state entry leaves the residual unchanged.
    for (int i = kVelocity; i < kExtrinsicRotation; ++i) {
      EXPECT_EQ(PointToPlaneResidual(BoxPlus(x, Delta(i, 1e-3)), p_lidar, plane, nullptr),
                PointToPlaneResidual(x, p_lidar, plane, nullptr));
    }
  }
}

// Near identity, a moderate rotation, and close to π.
INSTANTIATE_TEST_SUITE_P(RotationScales, JacobianTest, ::testing::Values(1e-9, 0.5, 1.75));

}  // namespace
}  // namespace hylo::estimation
