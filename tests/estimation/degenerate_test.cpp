// The IESKF update on synthetic scenes: a closed room is registered from a perturbed start;
// a flat plane and a long featureless corridor are reported as degenerate in the summary.
#include <gtest/gtest.h>

#include <random>

#include "hylo/estimation/ieskf/ieskf.h"
#include "hylo/estimation/initial_uncertainty.h"
#include "hylo/registration/brute_force_search.h"

namespace hylo::estimation {
namespace {

using hylo::PointCloud;

// Points on axis-aligned rectangles (one per face), spacing 0.1 m.
void AddFace(int fixed_axis, double fixed, Eigen::Vector2d lo, Eigen::Vector2d hi,
             PointCloud* points) {
  const int a = (fixed_axis + 1) % 3, b = (fixed_axis + 2) % 3;
  for (double u = lo.x(); u <= hi.x(); u += 0.1) {
    for (double v = lo.y(); v <= hi.y(); v += 0.1) {
      Eigen::Vector3f p;
      p[fixed_axis] = static_cast<float>(fixed);
      p[a] = static_cast<float>(u);
      p[b] = static_cast<float>(v);
      points->push_back(p);
    }
  }
}

PointCloud Floor() {
  PointCloud p;
  AddFace(2, 0.0, {-10, -10}, {10, 10}, &p);
  return p;
}
PointCloud Corridor() {  // along x: floor and two walls, no end
  PointCloud p;
  AddFace(2, 0.0, {-15, -1.5}, {15, 1.5}, &p);
  AddFace(1, -1.5, {0, -15}, {3, 15}, &p);
  AddFace(1, 1.5, {0, -15}, {3, 15}, &p);
  return p;
}
PointCloud Room() {
  PointCloud p;
  AddFace(2, 0.0, {-4, -6}, {4, 6}, &p);
  AddFace(0, -4.0, {-6, 0}, {6, 3}, &p);
  AddFace(0, 4.0, {-6, 0}, {6, 3}, &p);
  AddFace(1, -6.0, {0, -4}, {3, 4}, &p);
  AddFace(1, 6.0, {0, -4}, {3, 4}, &p);
  return p;
}

struct Outcome {
  UpdateSummary summary;
  lie::SE3d estimate;
};

// One scan of `map` seen from `T_true` (sensor 1.5 m up), estimated from T_true ⊕ error.
Outcome Register(const PointCloud& map, const lie::SE3d& T_true) {
  const registration::BruteForceSearch search(map);
  const registration::PlaneMatcher matcher(search, registration::PlaneMatcherOptions{});
  ImuOptions no_imu;
  no_imu.enabled = false;
  Ieskf filter(EstimatorOptions{}, no_imu);
  NavState x;
  x.R_map_imu = T_true.so3() * lie::SO3d::Exp(Eigen::Vector3d(0.01, -0.01, 0.02));
  x.p_map_imu = T_true.translation() + Eigen::Vector3d(0.08, -0.05, 0.04);
  // A prior as uncertain as the perturbation: 0.1 m, 0.1 rad (1 sigma).
  StateCovariance P0 = InitialUncertainty().SlamCovariance();
  P0.block<3, 3>(state_index::kPosition, state_index::kPosition).diagonal().setConstant(0.01);
  P0.block<3, 3>(state_index::kRotation, state_index::kRotation).diagonal().setConstant(0.01);
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

}  // namespace
}  // namespace hylo::estimation
