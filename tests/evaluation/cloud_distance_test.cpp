// The paper's cloud-to-cloud metric on cases small enough to compute by hand.
#include "hylo/evaluation/cloud_distance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "hylo/registration/brute_force_search.h"

namespace hylo::evaluation {
namespace {

using registration::BruteForceSearch;

TEST(CloudDistance, HandComputedStatistics) {
  // Reference: two points. Cloud: distances 0.1, 0.2, 0.3, 0.4 (inliers) and 2.0 (outlier).
  const BruteForceSearch reference(PointCloud{{0, 0, 0}, {10, 0, 0}});
  const PointCloud cloud = {{0.1f, 0, 0}, {0, 0.2f, 0}, {10, 0, 0.3f}, {9.6f, 0, 0}, {5, 2, 0}};
  CloudDistanceOptions options;
  options.max_distance_m = 1.0;
  const CloudDistanceSummary s = CloudToCloudDistance(cloud, reference, options);
  ASSERT_TRUE(s.ok) << s.message;
  EXPECT_EQ(s.num_points, 5u);
  EXPECT_EQ(s.count, 4u);
  EXPECT_EQ(s.num_rejected, 1u);
  EXPECT_DOUBLE_EQ(s.rejected_fraction, 0.2);
  // mean 0.25; population variance (0.15² + 0.05² + 0.05² + 0.15²) / 4 = 0.0125.
  EXPECT_NEAR(s.mean_m, 0.25, 1e-6);
  EXPECT_NEAR(s.std_m, std::sqrt(0.0125), 1e-6);
  EXPECT_NEAR(s.median_m, 0.25, 1e-6);
  EXPECT_NEAR(s.rms_m, std::sqrt((0.01 + 0.04 + 0.09 + 0.16) / 4.0), 1e-6);
  EXPECT_NEAR(s.max_m, 0.4, 1e-6);
}

TEST(CloudDistance, OddCountMedianAndIdenticalClouds) {
  const PointCloud points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const BruteForceSearch reference(points);
  const CloudDistanceSummary same = CloudToCloudDistance(points, reference);
  ASSERT_TRUE(same.ok);
  EXPECT_EQ(same.count, 3u);
  EXPECT_EQ(same.mean_m, 0.0);
  EXPECT_EQ(same.std_m, 0.0);
  // Distances 0.05, 0.1, 0.3 → median 0.1 (the middle one), max_distance 0.5 keeps all.
  const PointCloud shifted = {{0, 0, 0.05f}, {1, 0, 0.1f}, {0, 1.3f, 0}};
  const CloudDistanceSummary s = CloudToCloudDistance(shifted, reference);
  ASSERT_TRUE(s.ok);
  EXPECT_NEAR(s.median_m, 0.1, 1e-6);
  EXPECT_NEAR(s.mean_m, 0.15, 1e-6);
  EXPECT_EQ(s.num_rejected, 0u);
}

TEST(CloudDistance, ThresholdIsInclusiveAndNonFinitePointsAreCounted) {
  const BruteForceSearch reference(PointCloud{{0, 0, 0}});
  CloudDistanceOptions options;
  options.max_distance_m = 0.5;
  const PointCloud cloud = {{0.5f, 0, 0}, {0.5001f, 0, 0}, {std::nanf(""), 0, 0}};
  const CloudDistanceSummary s = CloudToCloudDistance(cloud, reference, options);
  EXPECT_EQ(s.num_nonfinite, 1u);
  EXPECT_EQ(s.num_points, 2u);
  EXPECT_EQ(s.count, 1u);
  EXPECT_DOUBLE_EQ(s.rejected_fraction, 0.5);
}

TEST(CloudDistance, BadInputGivesAStatusNotACrash) {
  const BruteForceSearch empty(PointCloud{});
  const BruteForceSearch one(PointCloud{{0, 0, 0}});
  const CloudDistanceSummary no_ref = CloudToCloudDistance(PointCloud{{1, 0, 0}}, empty);
  EXPECT_FALSE(no_ref.ok);
  EXPECT_EQ(no_ref.num_rejected, 1u);
  EXPECT_NE(no_ref.message.find("empty"), std::string::npos);
  const CloudDistanceSummary no_cloud = CloudToCloudDistance(PointCloud{}, one);
  EXPECT_FALSE(no_cloud.ok);
  EXPECT_FALSE(no_cloud.message.empty());
  CloudDistanceOptions bad;
  bad.max_distance_m = -1.0;
  std::string why;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("max_distance_m"), std::string::npos);
  const CloudDistanceSummary invalid = CloudToCloudDistance(PointCloud{{0, 0, 0}}, one, bad);
  EXPECT_FALSE(invalid.ok);
  EXPECT_NE(invalid.message.find("max_distance_m"), std::string::npos);
}

}  // namespace
}  // namespace hylo::evaluation
