// REP-105 frames and the covariance conversion of the ROS node, by property.

#include "frames.h"

#include <gtest/gtest.h>

#include <random>

#include "hylo/lie/so3.h"

namespace hylo::rosnode {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

Eigen::Isometry3d RandomPose(std::mt19937* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const Eigen::Quaterniond q(n(*rng), n(*rng), n(*rng), n(*rng));
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(n(*rng), n(*rng), n(*rng)) * 10.0;
  return T;
}

TEST(Frames, MapOdomBaseComposeToTheWorldPose) {
  std::mt19937 rng(7);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Isometry3d T_map_imu = RandomPose(&rng);
    const Eigen::Isometry3d T_map_odom = RandomPose(&rng);
    const Eigen::Vector3d origin(500123.25, 4100456.5, 120.0);
    const FramePoses poses = ComputeFramePoses(T_map_imu, T_map_odom, origin);
    const Eigen::Isometry3d chained = poses.T_world_odom * poses.T_odom_imu;
    EXPECT_LT((chained.matrix() - poses.T_world_imu.matrix()).norm(), 1e-6);
    EXPECT_LT((poses.T_world_imu.translation() - origin - T_map_imu.translation()).norm(), 1e-6);
    EXPECT_LT((poses.T_world_imu.linear() - T_map_imu.linear()).norm(), 1e-12);
  }
}

TEST(Frames, OdomEqualsMapWithoutRelocalization) {
  std::mt19937 rng(8);
  const Eigen::Isometry3d T_map_imu = RandomPose(&rng);
  const FramePoses poses =
      ComputeFramePoses(T_map_imu, Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero());
  EXPECT_LT((poses.T_odom_imu.matrix() - T_map_imu.matrix()).norm(), 1e-12);
  EXPECT_LT((poses.T_world_odom.matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-12);
}

// Samples [δp; δθ_body] from our covariance, perturbs the pose as the estimator does
// (p + δp, R·Exp(δθ)), measures the error the way ROS defines it (position difference and
// fixed-axis rotation Log(R' Rᵀ), both in the parent frame) and compares the sample
// covariance with PoseCovarianceToRos.
TEST(Frames, PoseCovarianceMatchesMonteCarloInTheParentAxes) {
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  Matrix6 A;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) A(r, c) = 0.02 * n(rng);
  }
  const Matrix6 sigma = A * A.transpose() + 1e-4 * Matrix6::Identity();
  const Eigen::Isometry3d T = RandomPose(&rng);
  const Eigen::Matrix3d R = T.linear();
  const std::array<double, 36> ros = PoseCovarianceToRos(sigma, Eigen::Matrix3d::Identity(), R);
  const Eigen::LLT<Matrix6> llt(sigma);
  const Matrix6 L = llt.matrixL();
  const int kSamples = 40000;
  Matrix6 sample_cov = Matrix6::Zero();
  for (int i = 0; i < kSamples; ++i) {
    Eigen::Matrix<double, 6, 1> z;
    for (int k = 0; k < 6; ++k) z(k) = n(rng);
    const Eigen::Matrix<double, 6, 1> delta = L * z;
    const Eigen::Matrix3d R_perturbed = R * lie::SO3d::Exp(delta.tail<3>()).Matrix();
    Eigen::Matrix<double, 6, 1> e;
    e.head<3>() = delta.head<3>();
    e.tail<3>() = lie::SO3d::FromMatrix(R_perturbed * R.transpose()).Log();
    sample_cov += e * e.transpose() / kSamples;
  }
  const double scale = sigma.diagonal().maxCoeff();
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      EXPECT_NEAR(ros[6 * r + c], sample_cov(r, c), 0.03 * scale) << "entry " << r << "," << c;
    }
  }
  // The body-axes covariance, copied without the rotation, must NOT match (the test can fail).
  double worst = 0.0;
  for (int r = 3; r < 6; ++r) {
    for (int c = 3; c < 6; ++c) worst = std::max(worst, std::abs(sigma(r, c) - sample_cov(r, c)));
  }
  EXPECT_GT(worst, 0.1 * scale);
}

TEST(Frames, TwistCovarianceIsCopiedRowMajor) {
  Matrix6 sigma;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) sigma(r, c) = 10 * r + c;
  }
  const std::array<double, 36> ros = TwistCovarianceToRos(sigma);
  EXPECT_EQ(ros[0 * 6 + 5], 5.0);
  EXPECT_EQ(ros[5 * 6 + 0], 50.0);
  EXPECT_EQ(ros[3 * 6 + 4], 34.0);
}

}  // namespace
}  // namespace hylo::rosnode
