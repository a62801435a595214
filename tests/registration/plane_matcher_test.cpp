// Plane fitting and matching against the exact (brute-force) neighbour search.
#include "hylo/registration/plane_matcher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "hylo/registration/brute_force_search.h"

namespace hylo::registration {
namespace {

// Points on the plane z = 0.2 x − 0.1 y + 3 with Gaussian noise along z.
PointCloud NoisyPlane(int n, double noise, std::mt19937* rng) {
  std::uniform_real_distribution<float> u(-10.f, 10.f);
  std::normal_distribution<float> g(0.f, static_cast<float>(noise));
  PointCloud points;
  for (int i = 0; i < n; ++i) {
    const float x = u(*rng), y = u(*rng);
    points.emplace_back(x, y, 0.2f * x - 0.1f * y + 3.f + g(*rng));
  }
  return points;
}

TEST(FitPlane, RecoversAKnownPlane) {
  std::mt19937 rng(7);
  std::vector<Neighbor> nb;
  for (const auto& p : NoisyPlane(50, 0.0, &rng)) nb.push_back({p, 0.f});
  Plane plane;
  ASSERT_TRUE(FitPlane(nb, 0.01f, &plane));
  const Eigen::Vector3d expected = Eigen::Vector3d(0.2, -0.1, -1.0).normalized();
  EXPECT_NEAR(std::abs(plane.normal.dot(expected)), 1.0, 1e-6);
  for (const Neighbor& n : nb) EXPECT_NEAR(plane.Distance(n.point.cast<double>()), 0.0, 1e-4);
}

TEST(FitPlane, RejectsNonPlanarCollinearAndTooFewPoints) {
  Plane plane;
  std::vector<Neighbor> corner = {{{0, 0, 0}, 0}, {{1, 0, 0}, 0}, {{0, 1, 0}, 0},
                                  {{0, 0, 1}, 0}, {{1, 1, 0}, 0}};
  EXPECT_FALSE(FitPlane(corner, 0.1f, &plane));
  std::vector<Neighbor> line = {{{0, 0, 0}, 0}, {{1, 1, 1}, 0}, {{2, 2, 2}, 0}, {{3, 3, 3}, 0}};
  EXPECT_FALSE(FitPlane(line, 0.1f, &plane));
  std::vector<Neighbor> two = {{{0, 0, 0}, 0}, {{1, 0, 0}, 0}};
  EXPECT_FALSE(FitPlane(two, 0.1f, &plane));
}

TEST(PlaneMatcher, MatchesNoisyPlaneAndAgreesWithBruteForceFit) {
  std::mt19937 rng(11);
  const BruteForceSearch map(NoisyPlane(4000, 0.01, &rng));
  // The plain path (no line-like retry) fits exactly the 5 nearest points; the default widens
  // an elongated set of 5 and finds the surface more closely.
  PlaneMatcherOptions plain;
  plain.line_like_neighbors = 0;
  const PlaneMatcher matcher(map, plain);
  const PlaneMatcher with_retry(map, PlaneMatcherOptions{});
  const Eigen::Vector3d truth = Eigen::Vector3d(0.2, -0.1, -1.0).normalized();
  std::uniform_real_distribution<double> u(-8.0, 8.0);
  int matched = 0;
  double worst_plain = 1.0, worst_widened = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double x = u(rng), y = u(rng);
    const Eigen::Vector3d q(x, y, 0.2 * x - 0.1 * y + 3.0 + 0.3);  // 0.3 m above the surface
    Plane plane;
    if (!matcher.Match(q, &plane)) continue;
    ++matched;
    std::vector<Neighbor> nb;
    map.KNearest(q.cast<float>(), 5, 2.f, &nb);
    Plane reference;
    ASSERT_TRUE(FitPlane(nb, 0.1f, &reference));
    EXPECT_NEAR(std::abs(plane.normal.dot(reference.normal)), 1.0, 1e-9);
    // The signed distance is the offset along the normal: |r| ≈ 0.3 cos(tilt).
    EXPECT_NEAR(std::abs(plane.Distance(q)), 0.3 / std::sqrt(1.0 + 0.04 + 0.01), 0.03);
    Plane widened;
    ASSERT_TRUE(with_retry.Match(q, &widened));
    worst_plain = std::min(worst_plain, std::abs(plane.normal.dot(truth)));
    worst_widened = std::min(worst_widened, std::abs(widened.normal.dot(truth)));
  }
  EXPECT_GT(matched, 190);
  // Random points ~0.3 m apart with 1 cm noise: the worst of the plain 5-point planes was 39
  // degrees off (a thin sliver of 5), the worst widened one 10 degrees.
  EXPECT_GT(worst_widened, 0.98);
  EXPECT_LT(worst_plain, worst_widened);
}

TEST(PlaneMatcher, RejectsFarAndNonPlanarNeighbourhoods) {
  PointCloud corner;
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j <= 10; ++j) {
      corner.emplace_back(0.1f * i, 0.1f * j, 0.f);  // floor
      corner.emplace_back(0.f, 0.1f * i, 0.1f * j);  // wall
    }
  }
  const BruteForceSearch map(corner);
  PlaneMatcherOptions options;
  options.planarity_threshold_m = 0.02f;
  const PlaneMatcher matcher(map, options);
  Plane plane;
  EXPECT_FALSE(matcher.Match(Eigen::Vector3d(0.02, 0.5, 0.02), &plane));  // at the edge
  EXPECT_TRUE(matcher.Match(Eigen::Vector3d(0.6, 0.5, 0.01), &plane));    // on the floor
  EXPECT_NEAR(std::abs(plane.normal.z()), 1.0, 1e-6);
  EXPECT_FALSE(matcher.Match(Eigen::Vector3d(20.0, 20.0, 0.0), &plane));  // out of range
}

// Two rings of a spinning head on flat ground (z = 0): points 0.5 m apart along x, the
// rings 1.2 m apart, ring A with a ±1 cm zigzag in height. A point above ring A has its five
// nearest neighbours on ring A alone.
PointCloud TwoRingsOnTheGround() {
  PointCloud points;
  for (int i = -20; i <= 20; ++i) {
    points.emplace_back(0.5f * i, 0.f, (i % 2 == 0) ? 0.01f : -0.01f);  // ring A
    points.emplace_back(0.5f * i, 1.2f, 0.f);                           // ring B
  }
  return points;
}

TEST(FitPlane, ReportsTheSpreadAcrossTheMainDirection) {
  std::mt19937 rng(7);
  std::vector<Neighbor> plane_points;
  for (const auto& p : NoisyPlane(50, 0.0, &rng)) plane_points.push_back({p, 0.f});
  Plane plane;
  NeighborSpread spread;
  ASSERT_TRUE(FitPlane(plane_points, 0.01, &plane, &spread));
  EXPECT_GT(spread.across_m, 3.0);  // uniform over 20 m x 20 m: ~5.8 m in either direction
  EXPECT_GE(spread.along_m, spread.across_m);
  std::vector<Neighbor> ring;
  for (int i = 0; i < 5; ++i) ring.push_back({{0.5f * i, 0.f, (i % 2 == 0) ? 0.01f : -0.01f}, 0.f});
  ASSERT_TRUE(FitPlane(ring, 0.1, &plane, &spread));
  EXPECT_LT(spread.across_m, 0.02);
  EXPECT_NEAR(spread.along_m, std::sqrt(0.5), 1e-3);  // 0, 0.5, ..., 2 m: variance 0.5 m^2
}

TEST(PlaneMatcher, ReachesAcrossALineOfNeighboursToTheGroundPlane) {
  const BruteForceSearch map(TwoRingsOnTheGround());
  const Eigen::Vector3d above_ring_a(0.1, 0.0, 0.05);
  Plane plane;
  // Five neighbours on ring A alone (no retry): the plane that fits them best is the vertical
  // one through the ring, and a scan matched to it is held sideways where ring A lay.
  PlaneMatcherOptions no_retry;
  no_retry.line_like_neighbors = 0;
  ASSERT_TRUE(PlaneMatcher(map, no_retry).Match(above_ring_a, &plane));
  EXPECT_GT(std::abs(plane.normal.y()), 0.99);
  // With the retry (the default) the line-like set is widened to twelve, which reach ring B:
  // the ground.
  ASSERT_TRUE(PlaneMatcher(map, PlaneMatcherOptions{}).Match(above_ring_a, &plane));
  EXPECT_GT(std::abs(plane.normal.z()), 0.999);
  EXPECT_NEAR(std::abs(plane.Distance(above_ring_a)), 0.05, 0.01);
}

// A dense patch of floor (0.1 m grid, 3 x 2 points) and, 0.3 m beyond it, a step 8 cm up.
// The five neighbours of a point on the patch spread 4.5 cm across and 7.7 cm along their main
// direction: under the planarity threshold in both, but a patch, not a line.
PointCloud DensePatchBesideAStep() {
  PointCloud points;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) {
      points.emplace_back(0.1f * i, 0.1f * j, 0.f);         // the patch
      points.emplace_back(0.5f + 0.1f * i, 0.1f * j, 0.08f);  // the step
    }
  }
  return points;
}

TEST(PlaneMatcher, ADensePatchIsNotLineLikeHoweverSmallItIs) {
  const BruteForceSearch map(DensePatchBesideAStep());
  const Eigen::Vector3d on_patch(0.09, 0.04, 0.02);
  Plane plane;
  std::vector<Neighbor> five;
  map.KNearest(on_patch.cast<float>(), 5, 2.f, &five);
  NeighborSpread spread;
  ASSERT_TRUE(FitPlane(five, 0.1, &plane, &spread));
  // What the two cases below rely on: under the planarity threshold, but not elongated.
  EXPECT_LT(spread.across_m, 0.1);
  EXPECT_GT(spread.across_m, 0.5 * spread.along_m);
  // Judged by the planarity threshold alone (ratio 1), the patch is widened to the step and
  // the plane through both tilts by ~9 degrees.
  PlaneMatcherOptions absolute_only;
  absolute_only.line_like_ratio = 1.0;
  ASSERT_TRUE(PlaneMatcher(map, absolute_only).Match(on_patch, &plane));
  EXPECT_LT(std::abs(plane.normal.z()), 0.995);
  // Judged against its spread along (the default ratio), the patch keeps its own plane: the
  // floor.
  ASSERT_TRUE(PlaneMatcher(map, PlaneMatcherOptions{}).Match(on_patch, &plane));
  EXPECT_GT(std::abs(plane.normal.z()), 0.9999);
  EXPECT_NEAR(std::abs(plane.Distance(on_patch)), 0.02, 1e-6);
}

TEST(PlaneMatcherOptions, NamesTheBrokenField) {
  PlaneMatcherOptions o;
  o.num_neighbors = 2;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("num_neighbors"), std::string::npos);
  PlaneMatcherOptions negative;
  negative.line_like_neighbors = -1;
  EXPECT_FALSE(negative.IsValid(&why));
  EXPECT_NE(why.find("line_like_neighbors"), std::string::npos);
  for (double ratio : {0.0, -0.1, 1.5, std::nan("")}) {
    PlaneMatcherOptions bad_ratio;
    bad_ratio.line_like_ratio = ratio;
    EXPECT_FALSE(bad_ratio.IsValid(&why)) << ratio;
    EXPECT_NE(why.find("line_like_ratio"), std::string::npos);
  }
}

}  // namespace
}  // namespace hylo::registration
