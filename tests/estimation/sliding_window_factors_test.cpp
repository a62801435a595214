// The smoother's Ceres pieces: the SO3 manifold's invariants (Ceres' own checks), every
// analytic factor Jacobian against Ceres' numeric differences through the manifold (the online
// calibration's for each set of its blocks), a scan's summarized cost against its points',
// residuals worked out by hand, and the Schur-complement marginalisation against the marginal
// of a known Gaussian.
#include "sliding_window_factors.h"

#include <ceres/gradient_checker.h>
#include <ceres/manifold_test_utils.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "calibration_factors.h"
#include "hylo/estimation/sliding_window/so3_manifold.h"
#include "hylo/registration/point_to_plane.h"
#include "marginalization.h"
#include "scan_plane_summary.h"

namespace hylo::estimation {
namespace {

Eigen::Vector3d RandomVector(std::mt19937* rng, double scale) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Vector3d(n(*rng), n(*rng), n(*rng)) * scale;
}

Eigen::Vector4d Quaternion(const Eigen::Vector3d& phi) {
  return lie::SO3d::Exp(phi).unit_quaternion().coeffs();
}

TEST(SO3Manifold, CeresInvariantsHold) {
  using namespace ceres;  // NOLINT: Ceres' macro below uses unqualified names
  const SO3Manifold manifold;
  std::mt19937 rng(1);
  // Generic rotations, one near identity and one near π.
  std::vector<Eigen::Vector3d> points{RandomVector(&rng, 1.0), Eigen::Vector3d(1e-9, 0, 0),
                                      Eigen::Vector3d(0, 0, M_PI - 1e-4)};
  for (const Eigen::Vector3d& phi : points) {
    const Eigen::Vector4d x = Quaternion(phi);
    const Eigen::Vector3d delta = RandomVector(&rng, 0.3);
    const Eigen::Vector4d y = Quaternion(lie::SO3d::Exp(phi).Log() + RandomVector(&rng, 0.2));
    EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-9);
  }
}

TEST(SO3Manifold, LiftedJacobianReturnsTheTangentOneThroughPlusJacobian) {
  std::mt19937 rng(2);
  const Eigen::Vector4d q = Quaternion(RandomVector(&rng, 1.0));
  Eigen::Matrix<double, 2, 3> tangent;
  tangent << RandomVector(&rng, 1.0).transpose(), RandomVector(&rng, 1.0).transpose();
  Eigen::Matrix<double, 2, 4, Eigen::RowMajor> ambient;
  LiftRotationJacobian<2>(q.data(), tangent, ambient.data());
  EXPECT_LT((ambient * RotationPlusJacobian(q.data()) - tangent).norm(), 1e-12);
}

// Ceres' GradientChecker differentiates numerically in the tangent space of each manifold.
// Compared per block by norm (its per-entry relative error flags round-off on zero entries).
void ExpectJacobiansCorrect(const ceres::CostFunction& cost,
                            const std::vector<const ceres::Manifold*>& manifolds,
                            std::vector<double*> parameters, double precision) {
  ceres::NumericDiffOptions options;
  const ceres::GradientChecker checker(&cost, &manifolds, options);
  ceres::GradientChecker::ProbeResults results;
  checker.Probe(parameters.data(), precision, &results);
  ASSERT_TRUE(results.return_value);
  for (std::size_t b = 0; b < parameters.size(); ++b) {
    const ceres::Matrix& analytic = results.local_jacobians[b];
    const ceres::Matrix& numeric = results.local_numeric_jacobians[b];
    EXPECT_LE((analytic - numeric).norm(), precision * std::max(1.0, numeric.norm()))
        << "block " << b << "\n"
        << analytic - numeric;
  }
}

TEST(SlidingWindowFactors, ImuFactorJacobians) {
  std::mt19937 rng(3);
  ImuPreintegration pre(Eigen::Vector3d(0.002, 0, -0.001), Eigen::Vector3d(0.03, 0.01, 0),
                        ImuNoise{});
  for (int k = 0; k < 20; ++k) {
    ImuInterval in;
    in.dt_s = 0.005;
    in.gyro_imu = RandomVector(&rng, 0.5);
    in.accel_imu = RandomVector(&rng, 1.0) + Eigen::Vector3d(0, 0, 9.81);
    pre.Integrate(in);
  }
  const Eigen::Vector3d g(0, 0, -9.81);
  const ImuFactor factor(pre);
  Eigen::Vector3d gravity = g + RandomVector(&rng, 0.01);
  StateBlocks a, b;
  NavState xi;
  xi.R_map_imu = lie::SO3d::Exp(RandomVector(&rng, 1.0));
  xi.v_map_imu = RandomVector(&rng, 1.0);
  xi.gyro_bias = Eigen::Vector3d(0.003, 0.001, 0.0);
  a.FromNavState(xi);
  NavState xj = pre.Predict(xi, g);
  xj.p_map_imu += RandomVector(&rng, 0.01);
  xj.R_map_imu = xj.R_map_imu * lie::SO3d::Exp(RandomVector(&rng, 0.01));
  b.FromNavState(xj);
  const SO3Manifold so3;
  // Whitened by very small IMU noise the residuals are large numbers: relative precision.
  ExpectJacobiansCorrect(
      factor, {&so3, nullptr, nullptr, &so3, nullptr, nullptr, nullptr},
      {a.rotation, a.position, a.speed_bias, b.rotation, b.position, b.speed_bias, gravity.data()},
      1e-6);
}

std::vector<PlaneMatch> RandomMatches(std::mt19937* rng, int count) {
  std::vector<PlaneMatch> matches(count);
  for (PlaneMatch& m : matches) {
    m.point_imu = RandomVector(rng, 10.0);
    m.plane.normal = RandomVector(rng, 1.0).normalized();
    m.plane.offset = RandomVector(rng, 1.0).x();
    m.sqrt_weight = 50.0;
  }
  return matches;
}

// Matches of a scan at the pose (R, p) in a map far from its origin: points up to 60 m out,
// each on its plane but for noise of σ 2 cm, weighted by 1/(5 cm), as the window sees them.
std::vector<PlaneMatch> MatchesNearPose(std::mt19937* rng, int count, const Eigen::Matrix3d& R,
                                        const Eigen::Vector3d& p) {
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<PlaneMatch> matches(count);
  for (PlaneMatch& m : matches) {
    m.point_imu = RandomVector(rng, 20.0);
    m.plane.normal = RandomVector(rng, 1.0).normalized();
    m.plane.offset = -m.plane.normal.dot(R * m.point_imu + p) + noise(*rng);
    m.sqrt_weight = 20.0;
  }
  return matches;
}

TEST(ScanPlaneSummary, HoldsThePointsCostAndItsNormalEquationsAtAnyPose) {
  std::mt19937 rng(4);
  const Eigen::Matrix3d R0 = lie::SO3d::Exp(RandomVector(&rng, 1.0)).Matrix();
  const Eigen::Vector3d p0(812.0, -455.0, 31.0);
  const std::vector<PlaneMatch> matches = MatchesNearPose(&rng, 2000, R0, p0);
  const ScanPlaneSummary summary = ScanPlaneSummary::Of(matches, p0 + RandomVector(&rng, 0.1));
  const ScanPlaneFactor factor(summary);
  // Near the optimum (where the cost is smallest and cancellation largest) and metres off.
  for (const double step : {0.0, 0.001, 0.05, 2.0}) {
    SCOPED_TRACE(::testing::Message() << "step " << step);
    const Eigen::Matrix3d R = R0 * lie::SO3d::Exp(RandomVector(&rng, step)).Matrix();
    const Eigen::Vector3d p = p0 + RandomVector(&rng, step);
    // One residual per point: the cost, JᵀJ and Jᵀr in the tangent [δθ, δp].
    double cost = 0.0;
    Eigen::Matrix<double, 6, 6> JtJ = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> Jtr = Eigen::Matrix<double, 6, 1>::Zero();
    for (const PlaneMatch& m : matches) {
      const double r = m.sqrt_weight * m.plane.Distance(R * m.point_imu + p);
      const registration::Vector6 J =
          m.sqrt_weight * registration::PointToPlaneJacobian(R, m.point_imu, m.plane);
      cost += r * r;
      JtJ += J * J.transpose();
      Jtr += J * r;
    }
    // The summary's 13 residuals, their Jacobian brought back to the tangent.
    const Eigen::Vector4d q = Eigen::Quaterniond(R).coeffs();
    const double* blocks[] = {q.data(), p.data()};
    Eigen::Matrix<double, 13, 1> r;
    Eigen::Matrix<double, 13, 4, Eigen::RowMajor> J_rotation;
    Eigen::Matrix<double, 13, 3, Eigen::RowMajor> J_position;
    double* jacobians[] = {J_rotation.data(), J_position.data()};
    ASSERT_TRUE(factor.Evaluate(blocks, r.data(), jacobians));
    Eigen::Matrix<double, 13, 6> J;
    J << J_rotation * RotationPlusJacobian(q.data()), J_position;
    EXPECT_NEAR(r.squaredNorm(), cost, 1e-9 * cost);
    EXPECT_LE((J.transpose() * J - JtJ).norm(), 1e-9 * JtJ.norm());
    EXPECT_LE((J.transpose() * r - Jtr).norm(), 1e-7 * std::max(1.0, Jtr.norm()));
  }
}

TEST(SlidingWindowFactors, ScanPlaneFactorJacobians) {
  std::mt19937 rng(4);
  const std::vector<PlaneMatch> matches = RandomMatches(&rng, 30);
  const ScanPlaneFactor factor(ScanPlaneSummary::Of(matches, RandomVector(&rng, 5.0)));
  Eigen::Vector4d q = Quaternion(RandomVector(&rng, 1.0));
  Eigen::Vector3d p = RandomVector(&rng, 5.0);
  const SO3Manifold so3;
  ExpectJacobiansCorrect(factor, {&so3, nullptr}, {q.data(), p.data()}, 1e-7);
}

TEST(SlidingWindowFactors, ScanPairFactorJacobians) {
  std::mt19937 rng(6);
  std::vector<PlaneMatch> matches(30);
  for (PlaneMatch& m : matches) {
    m.point_imu = RandomVector(&rng, 10.0);
    m.plane.normal = RandomVector(&rng, 1.0).normalized();  // in the earlier scan's frame
    m.plane.offset = RandomVector(&rng, 1.0).x();
    m.sqrt_weight = 50.0;
  }
  const ScanPairFactor factor(matches);
  Eigen::Vector4d q_a = Quaternion(RandomVector(&rng, 1.0));
  Eigen::Vector3d p_a = RandomVector(&rng, 5.0);
  Eigen::Vector4d q_b = Quaternion(RandomVector(&rng, 1.0));
  Eigen::Vector3d p_b = RandomVector(&rng, 5.0);
  const SO3Manifold so3;
  ExpectJacobiansCorrect(factor, {&so3, nullptr, &so3, nullptr},
                         {q_a.data(), p_a.data(), q_b.data(), p_b.data()}, 1e-7);
}

TEST(SlidingWindowFactors, ScanPairResidualIsThePointsDistanceToThePlaneSeenFromTheEarlierScan) {
  // Scan b sees the ground z = 0 of the map from 2 m up, level: its plane is z_b = -2. Scan a,
  // 1 m along x and 1.5 m up, sees a ground point 1.5 m below it: 0 m from the plane, and
  // raising scan a by 0.1 m raises the point 0.1 m above it.
  std::vector<PlaneMatch> matches(1);
  matches[0].point_imu = Eigen::Vector3d(3.0, 0.0, -1.5);
  matches[0].plane.normal = Eigen::Vector3d::UnitZ();
  matches[0].plane.offset = 2.0;
  const ScanPairFactor factor(matches);
  const Eigen::Vector4d level = Quaternion(Eigen::Vector3d::Zero());
  Eigen::Vector3d p_a(1.0, 0.0, 1.5);
  const Eigen::Vector3d p_b(0.0, 0.0, 2.0);
  const double* parameters[] = {level.data(), p_a.data(), level.data(), p_b.data()};
  double residual = 1.0;
  ASSERT_TRUE(factor.Evaluate(parameters, &residual, nullptr));
  EXPECT_NEAR(residual, 0.0, 1e-12);
  p_a.z() += 0.1;
  ASSERT_TRUE(factor.Evaluate(parameters, &residual, nullptr));
  EXPECT_NEAR(residual, 0.1, 1e-12);
}

TEST(CalibrationFactors, JacobiansForEveryLayout) {
  std::mt19937 rng(7);
  const std::vector<PlaneMatch> matches = RandomMatches(&rng, 30);
  const Eigen::Vector3d rate = RandomVector(&rng, 0.5);
  const Eigen::Vector3d lever_arm = RandomVector(&rng, 0.3);
  const SO3Manifold so3;
  for (const CalibrationLayout layout :
       {CalibrationLayout{true, false}, CalibrationLayout{false, true},
        CalibrationLayout{true, true}, CalibrationLayout{}}) {
    SCOPED_TRACE(::testing::Message()
                 << "time " << layout.time_offset << ", rotation " << layout.extrinsic_rotation);
    const CalibratedScanPlaneFactor factor(matches, layout, rate, lever_arm);
    Eigen::Vector4d q = Quaternion(RandomVector(&rng, 1.0));
    Eigen::Vector3d p = RandomVector(&rng, 5.0);
    Eigen::Matrix<double, 9, 1> speed_bias;
    speed_bias << RandomVector(&rng, 2.0), RandomVector(&rng, 0.01), RandomVector(&rng, 0.1);
    double time_offset = 0.015;
    Eigen::Vector4d extrinsic = Quaternion(RandomVector(&rng, 0.02));
    std::vector<const ceres::Manifold*> manifolds{&so3, nullptr, nullptr};
    std::vector<double*> blocks{q.data(), p.data(), speed_bias.data()};
    if (layout.time_offset) {
      manifolds.push_back(nullptr);
      blocks.push_back(&time_offset);
    }
    if (layout.extrinsic_rotation) {
      manifolds.push_back(&so3);
      blocks.push_back(extrinsic.data());
    }
    ExpectJacobiansCorrect(factor, manifolds, blocks, 1e-7);
  }
}

TEST(CalibrationFactors, NoCorrectionIsThePlainScanToMapFactor) {
  std::mt19937 rng(8);
  const std::vector<PlaneMatch> matches = RandomMatches(&rng, 20);
  const CalibratedScanPlaneFactor calibrated(matches, {true, true}, RandomVector(&rng, 0.5),
                                             RandomVector(&rng, 0.3));
  const Eigen::Vector4d q = Quaternion(RandomVector(&rng, 1.0));
  const Eigen::Vector3d p = RandomVector(&rng, 5.0);
  const ScanPlaneFactor plain(ScanPlaneSummary::Of(matches, p));
  Eigen::Matrix<double, 9, 1> speed_bias;
  speed_bias << RandomVector(&rng, 2.0), Eigen::Matrix<double, 6, 1>::Zero();
  const double time_offset = 0.0;
  const Eigen::Vector4d identity(0.0, 0.0, 0.0, 1.0);
  const double* calibrated_blocks[] = {q.data(), p.data(), speed_bias.data(), &time_offset,
                                       identity.data()};
  const double* plain_blocks[] = {q.data(), p.data()};
  std::vector<double> a(matches.size());
  Eigen::Matrix<double, ScanPlaneSummary::kDim, 1> b;
  ASSERT_TRUE(calibrated.Evaluate(calibrated_blocks, a.data(), nullptr));
  ASSERT_TRUE(plain.Evaluate(plain_blocks, b.data(), nullptr));
  const double cost = Eigen::Map<const Eigen::VectorXd>(a.data(), a.size()).squaredNorm();
  EXPECT_NEAR(b.squaredNorm(), cost, 1e-9 * cost);
}

TEST(CalibrationFactors, ResidualsWorkedOutByHand) {
  // A level vehicle at the origin driving 1 m/s along x while turning 0.25 rad/s left. A point
  // 5 m ahead, on the wall x = 5, taken 20 ms later than its stamp says: by then the vehicle
  // had gone 2 cm and turned 5 mrad, so the point is at 5 cos(0.005) + 0.02 along x.
  std::vector<PlaneMatch> wall(1);
  wall[0].point_imu = Eigen::Vector3d(5.0, 0.0, 0.0);
  wall[0].plane.normal = Eigen::Vector3d::UnitX();
  wall[0].plane.offset = -5.0;
  const Eigen::Vector4d level = Quaternion(Eigen::Vector3d::Zero());
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 9, 1> speed_bias = Eigen::Matrix<double, 9, 1>::Zero();
  speed_bias(0) = 1.0;
  const double time_offset = 0.02;
  const CalibratedScanPlaneFactor timed(wall, {true, false}, Eigen::Vector3d(0, 0, 0.25),
                                        Eigen::Vector3d::Zero());
  const double* timed_blocks[] = {level.data(), origin.data(), speed_bias.data(), &time_offset};
  double residual = 0.0;
  ASSERT_TRUE(timed.Evaluate(timed_blocks, &residual, nullptr));
  EXPECT_NEAR(residual, 0.02 - 5.0 * (1.0 - std::cos(0.005)), 1e-12);

  // Standing still, a lidar 1 m left of the IMU turned 0.01 rad further left than configured:
  // a point 5 m ahead of the lidar is 5 sin(0.01) further left, on the plane y = 1.
  std::vector<PlaneMatch> side(1);
  side[0].point_imu = Eigen::Vector3d(5.0, 1.0, 0.0);
  side[0].plane.normal = Eigen::Vector3d::UnitY();
  side[0].plane.offset = -1.0;
  const CalibratedScanPlaneFactor turned(side, {false, true}, Eigen::Vector3d::Zero(),
                                         Eigen::Vector3d(0.0, 1.0, 0.0));
  const Eigen::Vector4d Q = Quaternion(Eigen::Vector3d(0.0, 0.0, 0.01));
  speed_bias.setZero();
  const double* turned_blocks[] = {level.data(), origin.data(), speed_bias.data(), Q.data()};
  ASSERT_TRUE(turned.Evaluate(turned_blocks, &residual, nullptr));
  EXPECT_NEAR(residual, 5.0 * std::sin(0.01), 1e-12);
}

TEST(CalibrationFactors, PriorsAreWhitenedDistancesFromTheirCentres) {
  const std::unique_ptr<ceres::CostFunction> time(MakeTimeOffsetPriorFactor(0.01, 0.002));
  const double offset = 0.014;
  const double* time_blocks[] = {&offset};
  double r = 0.0;
  ASSERT_TRUE(time->Evaluate(time_blocks, &r, nullptr));
  EXPECT_NEAR(r, 2.0, 1e-12);

  const Eigen::Vector4d centre = Quaternion(Eigen::Vector3d(0.0, 0.0, 0.02));
  const std::unique_ptr<ceres::CostFunction> rotation(
      MakeRotationPriorFactor(centre.data(), 0.005));
  const Eigen::Vector4d Q = Quaternion(Eigen::Vector3d(0.0, 0.0, 0.03));
  const double* rotation_blocks[] = {Q.data()};
  Eigen::Vector3d residual;
  ASSERT_TRUE(rotation->Evaluate(rotation_blocks, residual.data(), nullptr));
  EXPECT_LT((residual - Eigen::Vector3d(0.0, 0.0, 2.0)).norm(), 1e-9);
}

TEST(SlidingWindowFactors, ConstantVelocityFactorJacobians) {
  std::mt19937 rng(5);
  std::unique_ptr<ceres::CostFunction> factor(MakeConstantVelocityFactor(0.1, 0.12, 1.0, 0.5));
  // Consecutive scans turn by tenths of a radian (autodiff is exact; the numeric reference
  // loses digits when the relative rotations approach π).
  const lie::SO3d Ra = lie::SO3d::Exp(RandomVector(&rng, 1.0));
  const lie::SO3d Rb = Ra * lie::SO3d::Exp(RandomVector(&rng, 0.2));
  const lie::SO3d Rc = Rb * lie::SO3d::Exp(RandomVector(&rng, 0.2));
  Eigen::Vector4d qa = Ra.unit_quaternion().coeffs(), qb = Rb.unit_quaternion().coeffs(),
                  qc = Rc.unit_quaternion().coeffs();
  Eigen::Vector3d pa = RandomVector(&rng, 1.0), pb = RandomVector(&rng, 1.0),
                  pc = RandomVector(&rng, 1.0);
  const SO3Manifold so3;
  ExpectJacobiansCorrect(*factor, {&so3, nullptr, &so3, nullptr, &so3, nullptr},
                         {qa.data(), pa.data(), qb.data(), pb.data(), qc.data(), pc.data()}, 1e-7);
}

TEST(SlidingWindowFactors, ZeroVelocityFactorWhitensTheVelocityOnly) {
  const ZeroVelocityFactor factor(0.02);
  double speed_bias[9] = {0.1, -0.2, 0.05, 1e-3, 2e-3, 3e-3, 0.1, 0.2, 0.3};
  const double* parameters[1] = {speed_bias};
  Eigen::Vector3d r;
  ASSERT_TRUE(factor.Evaluate(parameters, r.data(), nullptr));
  EXPECT_TRUE(r.isApprox(Eigen::Vector3d(5.0, -10.0, 2.5))) << r.transpose();
  ExpectJacobiansCorrect(factor, {nullptr}, {speed_bias}, 1e-7);
}

TEST(Marginalization, SchurComplementIsTheMarginalOfAGaussian) {
  // Two "states" (rotation + position each) with a random joint information H: marginalising
  // the first must leave exactly the information of the second's marginal, ((H⁻¹)_kk)⁻¹, and
  // the prior factor's Jacobians must be right at and away from the linearisation point.
  std::mt19937 rng(6);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Vector4d q0 = Quaternion(RandomVector(&rng, 1.0));
  Eigen::Vector4d q1 = Quaternion(RandomVector(&rng, 1.0));
  Eigen::Vector3d p0 = RandomVector(&rng, 1.0), p1 = RandomVector(&rng, 1.0);
  const std::vector<BlockRef> order{
      {q0.data(), 4, true}, {p0.data(), 3, false}, {q1.data(), 4, true}, {p1.data(), 3, false}};
  Eigen::MatrixXd A(12, 12);
  for (int i = 0; i < A.size(); ++i) A.data()[i] = n(rng);
  const Eigen::MatrixXd H = A * A.transpose() + Eigen::MatrixXd::Identity(12, 12);
  Eigen::VectorXd g(12);
  for (int i = 0; i < 12; ++i) g(i) = n(rng);
  const MarginalPrior joint = PriorFromInformation(order, H, g);
  const MarginalPriorFactor joint_factor(joint);
  const MarginalPrior marginal =
      Marginalize({{&joint_factor, {q0.data(), p0.data(), q1.data(), p1.data()}}}, order, 2);
  const Eigen::MatrixXd expected = H.inverse().bottomRightCorner(6, 6).inverse();
  const Eigen::MatrixXd got = marginal.J.transpose() * marginal.J;
  EXPECT_LT((got - expected).norm(), 1e-9 * expected.norm());
  const Eigen::VectorXd expected_g =
      g.tail(6) - H.bottomLeftCorner(6, 6) * H.topLeftCorner(6, 6).inverse() * g.head(6);
  EXPECT_LT((marginal.J.transpose() * marginal.r0 - expected_g).norm(), 1e-9 * expected_g.norm());

  const MarginalPriorFactor factor(marginal);
  const SO3Manifold so3;
  Eigen::Vector4d q_moved =
      Quaternion(lie::SO3d(Eigen::Quaterniond(q1.data())).Log() + RandomVector(&rng, 0.3));
  Eigen::Vector3d p_moved = p1 + RandomVector(&rng, 0.5);
  ExpectJacobiansCorrect(factor, {&so3, nullptr}, {q_moved.data(), p_moved.data()}, 1e-7);
}

}  // namespace
}  // namespace hylo::estimation
