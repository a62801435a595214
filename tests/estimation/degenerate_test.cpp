// The IESKF update on synthetic scenes: a closed room is registered from a perturbed start;
// a flat plane and a long featureless corridor are reported as degenerate in the summary; an
// online extrinsic held by the caller stays where it is.
#include <gtest/gtest.h>

#include <random>

#include "estimation/synthetic_scenes.h"
#include "hylo/estimation/ieskf/ieskf.h"
#include "hylo/estimation/initial_uncertainty.h"
#include "hylo/registration/brute_force_search.h"

namespace hylo::estimation {
namespace {

using hylo::PointCloud;
using hylo::testing::Corridor;
using hylo::testing::Floor;
using hylo::testing::Room;

struct Outcome {
  UpdateSummary summary;
  lie::SE3d estimate;
  lie::SE3d T_imu_lidar;  ///< the filter's extrinsic after the update
  StateCovariance P;
};

// The filter's online extrinsic in Register: off unless asked, started `extrinsic_error_rad`
// (rotation vector, lidar frame) off the true identity.
struct ExtrinsicSetup {
  bool online = false;
  bool held = false;
  Eigen::Vector3d extrinsic_error_rad = Eigen::Vector3d::Zero();
};

// One scan of `map` seen from `T_true` (sensor 1.5 m up), estimated from T_true ⊕ error.
Outcome Register(const PointCloud& map, const lie::SE3d& T_true,
                 const ExtrinsicSetup& extrinsic = {}) {
  const registration::BruteForceSearch search(map);
  const registration::PlaneMatcher matcher(search, registration::PlaneMatcherOptions{});
  ImuOptions no_imu;
  no_imu.enabled = false;
  EstimatorOptions options;
  options.ieskf.online_extrinsic = extrinsic.online;
  Ieskf filter(options, no_imu);
  filter.SetCalibrationHeld(extrinsic.held);
  NavState x;
  x.T_imu_lidar.so3() = lie::SO3d::Exp(extrinsic.extrinsic_error_rad);
  x.R_map_imu = T_true.so3() * lie::SO3d::Exp(Eigen::Vector3d(0.01, -0.01, 0.02));
  x.p_map_imu = T_true.translation() + Eigen::Vector3d(0.08, -0.05, 0.04);
  // A prior as uncertain as the perturbation: 0.1 m, 0.1 rad (1 sigma).
  StateCovariance P0 = InitialUncertainty().SlamCovariance();
  P0.block<3, 3>(state_index::kPosition, state_index::kPosition).diagonal().setConstant(0.01);
  P0.block<3, 3>(state_index::kRotation, state_index::kRotation).diagonal().setConstant(0.01);
  if (extrinsic.online) {
    // Correlated as a filter that had estimated the extrinsic for a while would be.
    using state_index::kExtrinsicRotation, state_index::kRotation;
    P0.block<3, 3>(kRotation, kExtrinsicRotation).diagonal().setConstant(-1e-5);
    P0.block<3, 3>(kExtrinsicRotation, kRotation).diagonal().setConstant(-1e-5);
  }
  filter.Initialize(x, P0);
  DeskewedScan scan;
  scan.t_ns = 0;
  const lie::SE3d T_true_inv = T_true.Inverse();
  for (std::size_t i = 0; i < map.size(); i += 7) {
    scan.points_lidar.push_back((T_true_inv * map[i].cast<double>()).cast<float>());
  }
  Outcome out;
  out.summary = filter.Update(scan, matcher);
  out.estimate = filter.state().T_map_imu();
  out.T_imu_lidar = filter.state().T_imu_lidar;
  out.P = filter.Covariance();
  return out;
}

TEST(IeskfGeometry, ClosedRoomIsRegisteredAndNotDegenerate) {
  const lie::SE3d T_true(lie::SO3d::Exp(Eigen::Vector3d(0, 0, 0.3)), Eigen::Vector3d(0.5, 1, 1.5));
  const Outcome out = Register(Room(), T_true);
  ASSERT_TRUE(out.summary.applied) << out.summary.message;
  EXPECT_FALSE(out.summary.degenerate) << out.summary.message;
  EXPECT_LT((out.estimate.translation() - T_true.translation()).norm(), 0.01)
      << out.summary.iterations << " iterations, converged " << out.summary.converged << ", "
      << out.summary.num_matches << " of " << out.summary.num_points << " matched, rms "
      << out.summary.rms_residual_m;
  EXPECT_LT(lie::Minus(out.estimate.so3(), T_true.so3()).norm(), 1e-3);
}

TEST(IeskfGeometry, FlatPlaneIsReportedDegenerate) {
  const lie::SE3d T_true(lie::SO3d(), Eigen::Vector3d(0, 0, 1.5));
  const Outcome out = Register(Floor(), T_true);
  const Outcome room = Register(Room(), T_true);
  ASSERT_TRUE(out.summary.applied) << out.summary.message;
  EXPECT_TRUE(out.summary.degenerate);
  // Far less information along the plane than a closed room gives in its weakest direction.
  EXPECT_LT(out.summary.min_translation_information,
            0.1 * room.summary.min_translation_information);
  EXPECT_NE(out.summary.message.find("degenerate"), std::string::npos);
  // What the plane does observe is right: height, roll and pitch.
  EXPECT_NEAR(out.estimate.translation().z(), 1.5, 0.01);
}

TEST(IeskfGeometry, LongCorridorIsReportedDegenerate) {
  const lie::SE3d T_true(lie::SO3d(), Eigen::Vector3d(0, 0, 1.5));
  const Outcome out = Register(Corridor(), T_true);
  const Outcome room = Register(Room(), T_true);
  ASSERT_TRUE(out.summary.applied) << out.summary.message;
  EXPECT_TRUE(out.summary.degenerate);
  EXPECT_LT(out.summary.min_translation_information,
            0.1 * room.summary.min_translation_information);
  EXPECT_NEAR(out.estimate.translation().y(), 0.0, 0.01);  // across the corridor: observed
}

// While searching, the supervisor holds the calibration: the scans then register against a
// map they built themselves. Held, the extrinsic and its covariance stay as they were, and its
// stale correlation with the pose is dropped; released, the same update moves it.
TEST(IeskfGeometry, AHeldExtrinsicStaysWhereItIs) {
  const lie::SE3d T_true(lie::SO3d::Exp(Eigen::Vector3d(0, 0, 0.3)), Eigen::Vector3d(0.5, 1, 1.5));
  ExtrinsicSetup setup;
  setup.online = true;
  setup.held = true;
  setup.extrinsic_error_rad = Eigen::Vector3d(0.02, 0.0, 0.0);
  const Outcome held = Register(Room(), T_true, setup);
  ASSERT_TRUE(held.summary.applied) << held.summary.message;
  const lie::SO3d started = lie::SO3d::Exp(setup.extrinsic_error_rad);
  EXPECT_EQ(lie::Minus(held.T_imu_lidar.so3(), started).norm(), 0.0);
  EXPECT_EQ(held.T_imu_lidar.translation().norm(), 0.0);
  using state_index::kDimNoExtrinsic;
  const StateCovariance P0 = InitialUncertainty().SlamCovariance();
  EXPECT_EQ((held.P.bottomRightCorner<6, 6>() - P0.bottomRightCorner<6, 6>()).norm(), 0.0);
  EXPECT_EQ(held.P.block(0, kDimNoExtrinsic, kDimNoExtrinsic, 6).norm(), 0.0);
  // The pose takes up the whole tilt the scan shows: the extrinsic's error, turned.
  EXPECT_LT(lie::Minus(held.estimate.so3() * started, T_true.so3()).norm(), 1e-3);

  setup.held = false;
  const Outcome released = Register(Room(), T_true, setup);
  ASSERT_TRUE(released.summary.applied) << released.summary.message;
  EXPECT_GT(lie::Minus(released.T_imu_lidar.so3(), started).norm(), 1e-4);
}

}  // namespace
}  // namespace hylo::estimation
