// The localizer's per-scan health: a scan registered where it belongs fits the map surface;
// one tilted by a few degrees or shifted off the walls does not, even in a dense map where
// most points still have a map point nearby.
#include <gtest/gtest.h>

#include <cmath>

#include "hylo/estimation/localization.h"
#include "hylo/mapping/ikd_tree.h"

namespace hylo::estimation {
namespace {

// A 20 m × 20 m room: floor and four walls 3 m high, sampled every `step_m`, offset by
// `phase_m` so that the scan's points are not the map's.
registration::PointCloud Room(float step_m, float phase_m) {
  registration::PointCloud points;
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

registration::PointCloud Moved(const registration::PointCloud& points, double angle_deg,
                               const Eigen::Vector3f& axis, const Eigen::Vector3f& shift_m) {
  const Eigen::Matrix3f R =
      Eigen::AngleAxisf(static_cast<float>(angle_deg * M_PI / 180.0), axis).toRotationMatrix();
  registration::PointCloud moved;
  for (const Eigen::Vector3f& p : points) moved.push_back(R * p + shift_m);
  return moved;
}

class ScanHealthTest : public ::testing::Test {
 protected:
  ScanHealthTest() : planes_(map_, registration::PlaneMatcherOptions()) {
    map_.Build(Room(0.1f, 0.0f));
  }
  ScanHealth Health(const registration::PointCloud& scan, std::size_t matches = 1000) const {
    return EvaluateScanHealth(scan, planes_, matches, options_);
  }
  mapping::IkdTree map_;
  registration::PlaneMatcher planes_;
  LocalizationOptions options_;
  const registration::PointCloud scan_ = Room(0.3f, 0.05f);
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

TEST_F(ScanHealthTest, AnEmptyScanOrMapIsNotGood) {
  EXPECT_FALSE(Health(registration::PointCloud()).good);
  const mapping::IkdTree empty;
  const registration::PlaneMatcher no_planes(empty, registration::PlaneMatcherOptions());
  EXPECT_FALSE(EvaluateScanHealth(scan_, no_planes, 1000, options_).good);
}

}  // namespace
}  // namespace hylo::estimation
