// Trajectory metrics on synthetic trajectories whose answers are computed by hand.
#include "hylo/evaluation/trajectory_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hylo::evaluation {
namespace {

constexpr int64_t kSecond = 1'000'000'000;
constexpr double kDeg = M_PI / 180.0;

Eigen::Isometry3d Pose(const Eigen::Vector3d& t, double yaw = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = t;
  return T;
}

// A rising helix: not collinear, so SE(3)/Sim(3) alignment is determined.
std::vector<TimedPose> Circle(int n) {
  std::vector<TimedPose> poses;
  for (int i = 0; i < n; ++i) {
    TimedPose p;
    p.t_ns = i * 100'000'000LL;
    const double a = 0.05 * i;
    p.T_world_body = Pose(Eigen::Vector3d(10 * std::cos(a), 10 * std::sin(a), 0.1 * a), a);
    poses.push_back(p);
  }
  return poses;
}

Eigen::Isometry3d Offset() {
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  offset.linear() =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  offset.translation() = Eigen::Vector3d(5, -3, 2);
  return offset;
}

TEST(TrajectoryMetrics, AlignmentRemovesARigidOffsetExactly) {
  const std::vector<TimedPose> reference = Circle(100);
  std::vector<TimedPose> estimate = reference;
  for (TimedPose& p : estimate) p.T_world_body = Offset() * p.T_world_body;
  for (Alignment a : {Alignment::kSE3, Alignment::kSim3, Alignment::kFirstPose}) {
    AteOptions options;
    options.alignment = a;
    const AteResult ate = ComputeAte(estimate, reference, options);
    ASSERT_TRUE(ate.ok) << ate.message;
    EXPECT_EQ(ate.num_poses, 100u);
    EXPECT_LT(ate.rmse_m, 1e-9) << ToString(a);
    EXPECT_LT(ate.rotation_max_deg, 1e-6) << ToString(a);
    EXPECT_NEAR(ate.scale, 1.0, 1e-12);
    EXPECT_TRUE(ate.T_reference_estimate.isApprox(Offset().inverse(), 1e-9));
  }
  const AteResult ate = ComputeAte(estimate, reference);
  EXPECT_LT(ate.end_drift_m, 1e-9);
  EXPECT_NEAR(ate.path_length_m, 10 * 0.05 * 99, 0.05);  // arc 4.95 rad of a 10 m radius
}

TEST(TrajectoryMetrics, AlternatingErrorCannotBeAlignedAway) {
  const std::vector<TimedPose> reference = Circle(100);
  std::vector<TimedPose> estimate = reference;
  // Alternating ±3 cm along z: without alignment every error is 3 cm.
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    estimate[i].T_world_body.translation().z() += (i % 2 == 0 ? 0.03 : -0.03);
  }
  AteOptions none;
  none.alignment = Alignment::kNone;
  const AteResult raw = ComputeAte(estimate, reference, none);
  ASSERT_TRUE(raw.ok) << raw.message;
  EXPECT_NEAR(raw.rmse_m, 0.03, 1e-12);
  EXPECT_NEAR(raw.median_m, 0.03, 1e-12);
  EXPECT_NEAR(raw.max_m, 0.03, 1e-12);
  EXPECT_LT(raw.std_m, 1e-12);
  // SE(3) minimises the RMSE, so it can only lower it, and a zero-mean zigzag leaves almost
  // nothing to remove.
  const AteResult aligned = ComputeAte(estimate, reference);
  EXPECT_LE(aligned.rmse_m, raw.rmse_m + 1e-12);
  EXPECT_GT(aligned.rmse_m, 0.029);
}

TEST(TrajectoryMetrics, ConstantOffsetWithoutAlignmentAndLinearDriftFromTheFirstPose) {
  const std::vector<TimedPose> reference = Circle(100);
  std::vector<TimedPose> shifted = reference, drifting = reference;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    shifted[i].T_world_body.translation() += Eigen::Vector3d(0.0, 0.1, 0.0);
    drifting[i].T_world_body.translation() += Eigen::Vector3d(0.01 * i, 0.0, 0.0);
  }
  AteOptions none;
  none.alignment = Alignment::kNone;
  const AteResult a = ComputeAte(shifted, reference, none);
  EXPECT_NEAR(a.rmse_m, 0.1, 1e-12);
  EXPECT_NEAR(a.mean_m, 0.1, 1e-12);
  EXPECT_NEAR(a.median_m, 0.1, 1e-12);
  EXPECT_NEAR(a.max_m, 0.1, 1e-12);
  EXPECT_LT(ComputeAte(shifted, reference).rmse_m, 1e-9);  // SE(3) removes it
  // Error i·1 cm for i = 0..99 with the first poses aligned: mean 0.495, median 0.495,
  // max 0.99, RMSE 0.01·sqrt(Σi²/100) = 0.01·sqrt(3283.5).
  AteOptions first;
  first.alignment = Alignment::kFirstPose;
  const AteResult d = ComputeAte(drifting, reference, first);
  ASSERT_TRUE(d.ok) << d.message;
  EXPECT_NEAR(d.mean_m, 0.495, 1e-9);
  EXPECT_NEAR(d.median_m, 0.495, 1e-9);
  EXPECT_NEAR(d.max_m, 0.99, 1e-9);
  EXPECT_NEAR(d.rmse_m, 0.01 * std::sqrt(3283.5), 1e-9);
  EXPECT_NEAR(d.end_drift_m, 0.99, 1e-9);
}

TEST(TrajectoryMetrics, Sim3RecoversAKnownScale) {
  const std::vector<TimedPose> reference = Circle(100);
  std::vector<TimedPose> estimate = reference;
  // The estimate is the reference shrunk by 2 and moved: x_est = Offset(x_ref / 2).
  for (TimedPose& p : estimate) {
    p.T_world_body.translation() *= 0.5;
    p.T_world_body = Offset() * p.T_world_body;
  }
  AteOptions sim3;
  sim3.alignment = Alignment::kSim3;
  const AteResult ate = ComputeAte(estimate, reference, sim3);
  ASSERT_TRUE(ate.ok) << ate.message;
  EXPECT_NEAR(ate.scale, 2.0, 1e-9);
  EXPECT_LT(ate.rmse_m, 1e-9);
  EXPECT_LT(ate.rotation_max_deg, 1e-6);
  EXPECT_GT(ComputeAte(estimate, reference).rmse_m, 1.0);  // SE(3) cannot fix a scale
}

TEST(TrajectoryMetrics, NearestAssociationRespectsTheTolerance) {
  std::vector<TimedPose> reference, estimate;
  for (int i = 0; i <= 20; ++i) {  // 1 m/s along x, 10 Hz
    reference.push_back({i * kSecond / 10, Pose(Eigen::Vector3d(0.1 * i, 0, 0))});
  }
  for (int i = 0; i < 20; ++i) {  // stamps 30 ms late, positions exact at those stamps
    const int64_t t_ns = i * kSecond / 10 + 30'000'000;
    estimate.push_back({t_ns, Pose(Eigen::Vector3d(1e-9 * t_ns, 0, 0))});
  }
  AssociationOptions nearest;
  nearest.method = Association::kNearest;
  nearest.max_dt_ns = 20'000'000;
  EXPECT_EQ(Associate(estimate, reference, nearest).t_ns.size(), 0u);
  EXPECT_EQ(Associate(estimate, reference, nearest).num_unmatched, 20u);
  nearest.max_dt_ns = 40'000'000;
  AteOptions options;
  options.association = nearest;
  options.alignment = Alignment::kNone;
  const AteResult near = ComputeAte(estimate, reference, options);
  EXPECT_EQ(near.num_poses, 20u);
  EXPECT_NEAR(near.mean_m, 0.03, 1e-9);  // 30 ms at 1 m/s
  options.association.method = Association::kInterpolate;
  const AteResult interp = ComputeAte(estimate, reference, options);
  EXPECT_EQ(interp.num_poses, 20u);
  EXPECT_LT(interp.max_m, 1e-9);
}

TEST(TrajectoryMetrics, InterpolationRefusesHolesAndStampsOutsideTheSpan) {
  const std::vector<TimedPose> reference = {
      {0, Pose({0, 0, 0})}, {kSecond, Pose({1, 0, 0}, 0.2)}, {4 * kSecond, Pose({4, 0, 0}, 0.2)}};
  // Reverse order on purpose: association sorts.
  const std::vector<TimedPose> estimate = {{5 * kSecond, Pose({0, 0, 0})},
                                           {2 * kSecond, Pose({0, 0, 0})},
                                           {kSecond / 2, Pose({0, 0, 0})}};
  const AssociatedPoses pairs = Associate(estimate, reference);  // max gap 1 s
  ASSERT_EQ(pairs.t_ns.size(), 1u);
  EXPECT_EQ(pairs.t_ns[0], kSecond / 2);
  EXPECT_EQ(pairs.num_unmatched, 2u);
  EXPECT_TRUE(pairs.reference[0].translation().isApprox(Eigen::Vector3d(0.5, 0, 0)));
  EXPECT_NEAR(Eigen::AngleAxisd(pairs.reference[0].linear()).angle(), 0.1, 1e-12);  // slerp
  AssociationOptions wide;
  wide.max_gap_ns = 3 * kSecond;
  EXPECT_EQ(Associate(estimate, reference, wide).t_ns.size(), 2u);
}

// A 10 m square driven in 1 m steps; a yaw turn of 90° ends every 10th step. The estimate
// over-measures each step by 1 % and over-turns each corner by 0.5°.
void Square(std::vector<TimedPose>* reference, std::vector<TimedPose>* estimate,
            double corner_error_rad) {
  Eigen::Isometry3d Q = Eigen::Isometry3d::Identity(), P = Q;
  for (int k = 0; k <= 40; ++k) {
    reference->push_back({k * kSecond, Q});
    estimate->push_back({k * kSecond, P});
    const bool corner = k % 10 == 9;
    Q = Q * Pose({1.0, 0, 0}, corner ? M_PI / 2 : 0.0);
    P = P * Pose({1.01, 0, 0}, corner ? M_PI / 2 + corner_error_rad : 0.0);
  }
}

TEST(TrajectoryMetrics, RpeOnASquareWithAKnownDrift) {
  std::vector<TimedPose> reference, estimate;
  Square(&reference, &estimate, 0.5 * kDeg);
  // One frame: E = Rz(-θ) T(0.01 x) Rz(θ'), so |t| = 1 cm for all 40 pairs; the angle is
  // 0.5° at the 4 corners and 0 elsewhere.
  const RpeResult one = ComputeRpe(estimate, reference);
  ASSERT_TRUE(one.ok) << one.message;
  EXPECT_EQ(one.num_pairs, 40u);
  EXPECT_NEAR(one.rmse_m, 0.01, 1e-9);
  EXPECT_NEAR(one.max_m, 0.01, 1e-9);
  EXPECT_NEAR(one.rotation_max_deg, 0.5, 1e-9);
  EXPECT_NEAR(one.rotation_mean_deg, 0.5 * 4 / 40, 1e-9);
  EXPECT_NEAR(one.rotation_rmse_deg, std::sqrt(0.25 * 4 / 40), 1e-9);
  EXPECT_NEAR(one.rotation_median_deg, 0.0, 1e-9);
  // RPE ignores where the estimate's world frame is.
  std::vector<TimedPose> moved = estimate;
  for (TimedPose& p : moved) p.T_world_body = Offset() * p.T_world_body;
  EXPECT_NEAR(ComputeRpe(moved, reference).rmse_m, one.rmse_m, 1e-9);
}

TEST(TrajectoryMetrics, RpeOverADistanceDelta) {
  std::vector<TimedPose> reference, estimate;
  Square(&reference, &estimate, 0.0);
  // 2 m apart: a 1 % scale error gives 1 % of the displacement: 2 cm on a straight side,
  // 1.414 cm for the 3 pairs that turn a corner (i = 9, 19, 29); 39 pairs.
  RpeOptions options;
  options.unit = DeltaUnit::kMeters;
  options.delta = 2.0;
  const RpeResult rpe = ComputeRpe(estimate, reference, options);
  ASSERT_TRUE(rpe.ok) << rpe.message;
  EXPECT_EQ(rpe.num_pairs, 39u);
  EXPECT_NEAR(rpe.max_m, 0.02, 1e-9);
  EXPECT_NEAR(rpe.mean_m, (36 * 0.02 + 3 * 0.01 * std::sqrt(2.0)) / 39, 1e-9);
  EXPECT_NEAR(rpe.median_m, 0.02, 1e-9);
  EXPECT_NEAR(rpe.rotation_max_deg, 0.0, 1e-9);
  options.unit = DeltaUnit::kFrames;  // 2 frames = 2 m here
  EXPECT_NEAR(ComputeRpe(estimate, reference, options).mean_m, rpe.mean_m, 1e-12);
}

TEST(TrajectoryMetrics, BadInputGivesAMessageNotACrash) {
  std::vector<TimedPose> line;
  for (int i = 0; i < 10; ++i) line.push_back({i * kSecond, Pose({1.0 * i, 0, 0})});
  const AteResult collinear = ComputeAte(line, line);
  EXPECT_FALSE(collinear.ok);
  EXPECT_NE(collinear.message.find("collinear"), std::string::npos);
  AteOptions first;
  first.alignment = Alignment::kFirstPose;
  EXPECT_TRUE(ComputeAte(line, line, first).ok);
  EXPECT_FALSE(ComputeAte({}, line).ok);
  EXPECT_FALSE(ComputeAte(line, {}).message.empty());
  RpeOptions bad;
  bad.delta = 1.5;
  std::string why;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("delta"), std::string::npos);
  EXPECT_FALSE(ComputeRpe(line, line, bad).ok);
  bad.delta = 20;  // longer than the trajectory
  const RpeResult none = ComputeRpe(line, line, bad);
  EXPECT_FALSE(none.ok);
  EXPECT_FALSE(none.message.empty());
  const ErrorStatistics empty = ComputeStatistics({});
  EXPECT_EQ(empty.count, 0u);
}

}  // namespace
}  // namespace hylo::evaluation
