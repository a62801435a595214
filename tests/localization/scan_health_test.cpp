// The localizer's per-scan health, read from the update's own residuals: a scan registered
// where it belongs fits the map surface; one tilted by a few degrees or shifted off the walls
// does not, even in a dense map where most points still have a map point nearby. And both
// back-ends report those residuals for every point of the scan.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "hylo/estimation/estimator_options.h"
#include "hylo/estimation/imu_options.h"
#include "hylo/estimation/initial_uncertainty.h"
#include "hylo/localization/localization.h"
#include "hylo/mapping/ikd_tree.h"

namespace hylo::localization {
namespace {

// A 20 m × 20 m room: floor and four walls 3 m high, sampled every `step_m`, offset by
// `phase_m` so that the scan's points are not the map's.
PointCloud Room(float step_m, float phase_m) {
  PointCloud points;
  for (float a = -10.0f + phase_m; a < 10.0f; a += step_m) {
    for (float b = -10.0f + phase_m; b < 10.0f; b += step_m) points.emplace_back(a, b, 0.0f);
    for (float z = phase_m; z < 3.0f; z += step_m) {
      points.emplace_back(a, -10.0f, z);
      points.emplace_back(a, 10.0f, z);
      points.emplace_back(-10.0f, a, z);
      points.emplace_back(10.0f, a, z);
    }
  }
  return points;
}

PointCloud Moved(const PointCloud& points, double angle_deg, const Eigen::Vector3f& axis,
                 const Eigen::Vector3f& shift_m) {
  const Eigen::Matrix3f R =
      Eigen::AngleAxisf(static_cast<float>(angle_deg * M_PI / 180.0), axis).toRotationMatrix();
  PointCloud moved;
  for (const Eigen::Vector3f& p : points) moved.push_back(R * p + shift_m);
  return moved;
}

class ScanHealthTest : public ::testing::Test {
 protected:
  ScanHealthTest() : planes_(map_, registration::PlaneMatcherOptions()) {
    map_.Build(Room(0.1f, 0.0f));
  }
  // What an update registering `scan_map` (already in the map frame) would report: each
  // point's residual to the plane of its nearest map points, NaN without one.
  estimation::UpdateSummary UpdateAt(const PointCloud& scan_map, std::size_t matches = 1000) const {
    estimation::UpdateSummary update;
    update.num_points = scan_map.size();
    update.num_matches = matches;
    for (const Eigen::Vector3f& p : scan_map) {
      registration::Plane plane;
      update.point_residuals_m.push_back(planes_.Match(p.cast<double>(), &plane)
                                             ? static_cast<float>(plane.Distance(p.cast<double>()))
                                             : std::numeric_limits<float>::quiet_NaN());
    }
    return update;
  }
  ScanHealth Health(const PointCloud& scan, std::size_t matches = 1000) const {
    return EvaluateScanHealth(UpdateAt(scan, matches), options_);
  }
  mapping::IkdTree map_;
  registration::PlaneMatcher planes_;
  LocalizationOptions options_;
  const PointCloud scan_ = Room(0.3f, 0.05f);
};

TEST_F(ScanHealthTest, AScanWhereItBelongsIsGood) {
  const ScanHealth h = Health(scan_);
  EXPECT_GT(h.inlier_ratio, 0.95);
  EXPECT_LT(h.fitness_m2, 0.01);
  EXPECT_TRUE(h.good);
}

TEST_F(ScanHealthTest, TiltedAFewDegreesIsBadThoughMostPointsHaveAMapPointNearby) {
  // 3° about the x axis through the room's centre: floor points move by up to 0.5 m, half of
  // them by less than 0.26 m (a nearest-point test within 0.3 m would pass those), and the
  // walls at x = ±10 m slide within their own planes (they fit: nothing shows that error).
  const ScanHealth h =
      Health(Moved(scan_, 3.0, Eigen::Vector3f::UnitX(), Eigen::Vector3f::Zero()));
  EXPECT_LT(h.inlier_ratio, options_.min_inlier_ratio);
  EXPECT_FALSE(h.good);
}

TEST_F(ScanHealthTest, ShiftedOffTheWallsIsBad) {
  const ScanHealth h = Health(Moved(scan_, 0.0, Eigen::Vector3f::UnitZ(), Eigen::Vector3f(0.25f, 0.25f, 0.25f)));
  EXPECT_LT(h.inlier_ratio, options_.min_inlier_ratio);
  EXPECT_FALSE(h.good);
}

TEST_F(ScanHealthTest, TooFewPlaneMatchesIsBadEvenWhenTheFitIsGood) {
  const ScanHealth h = Health(scan_, options_.min_matches - 1);
  EXPECT_GT(h.inlier_ratio, 0.95);
  EXPECT_FALSE(h.good);
}

TEST_F(ScanHealthTest, AnEmptyScanOrAnUpdateWithoutResidualsIsNotGood) {
  EXPECT_FALSE(Health(PointCloud()).good);
  estimation::UpdateSummary not_applied;  // e.g. too few matches: no residuals reported
  not_applied.num_points = scan_.size();
  EXPECT_FALSE(EvaluateScanHealth(not_applied, options_).good);
}

class UpdateResidualsTest : public ScanHealthTest,
                            public ::testing::WithParamInterface<estimation::Estimator::Backend> {};

TEST_P(UpdateResidualsTest, EveryPointGetsItsResidualAtTheFinalPose) {
  // The room's scan from 5 cm and 1° off: the update pulls it back, and its residuals say so.
  estimation::EstimatorOptions options;
  options.backend = GetParam();
  // The smoother's per-scan wall-time budget (50 ms) is for real time; under a sanitizer or on
  // a loaded machine its first iteration may not fit, and this test is about the residuals.
  options.sliding_window.max_solver_time_s = 10.0;
  estimation::ImuOptions no_imu;
  no_imu.enabled = false;
  const std::unique_ptr<estimation::Estimator> estimator = estimation::Estimator::Create(options, no_imu);
  estimation::NavState start;
  start.R_map_imu = lie::SO3d::Exp(Eigen::Vector3d(0.0, 0.0, M_PI / 180.0));
  start.p_map_imu = Eigen::Vector3d(0.05, -0.03, 0.02);
  estimator->Initialize(start, estimation::InitialUncertainty().LocalizedCovariance());
  estimation::DeskewedScan scan;
  scan.t_ns = 0;
  scan.points_lidar = scan_;  // the true pose is the identity
  const estimation::UpdateSummary update = estimator->Update(scan, planes_);
  ASSERT_TRUE(update.applied) << update.message;
  ASSERT_EQ(update.point_residuals_m.size(), scan_.size());
  std::size_t with_plane = 0;
  for (float r : update.point_residuals_m) with_plane += std::isfinite(r) ? 1 : 0;
  EXPECT_GE(with_plane, update.num_matches);
  const ScanHealth from_update = EvaluateScanHealth(update, options_);
  EXPECT_TRUE(from_update.good);
  EXPECT_GT(from_update.inlier_ratio, 0.9);
  EXPECT_NEAR(from_update.inlier_ratio, Health(scan_).inlier_ratio, 0.05);
  EXPECT_LT(estimator->state().p_map_imu.norm(), 0.01);
}

INSTANTIATE_TEST_SUITE_P(BothBackends, UpdateResidualsTest,
                         ::testing::Values(estimation::Estimator::Backend::kIeskf,
                                           estimation::Estimator::Backend::kSlidingWindow),
                         [](const auto& info) { return ToString(info.param); });

}  // namespace
}  // namespace hylo::localization
