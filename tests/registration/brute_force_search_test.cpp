#include "hylo/registration/brute_force_search.h"

#include <gtest/gtest.h>

namespace hylo::registration {
namespace {

TEST(BruteForceSearch, ReturnsNearestFirstWithinMaxDistance) {
  BruteForceSearch search({{0, 0, 0}, {3, 0, 0}, {1, 0, 0}, {2, 0, 0}, {10, 0, 0}});
  std::vector<Neighbor> nn;
  search.KNearest({0.1f, 0, 0}, 3, 5.f, &nn);
  ASSERT_EQ(nn.size(), 3u);
  EXPECT_FLOAT_EQ(nn[0].point.x(), 0.f);
  EXPECT_FLOAT_EQ(nn[1].point.x(), 1.f);
  EXPECT_FLOAT_EQ(nn[2].point.x(), 2.f);
  EXPECT_NEAR(nn[1].squared_distance, 0.81f, 1e-5f);
  search.KNearest({0.1f, 0, 0}, 10, 2.5f, &nn);
  EXPECT_EQ(nn.size(), 3u) << "points beyond max_distance must be excluded";
}

TEST(BruteForceSearch, EmptyIndexGivesNoNeighbours) {
  BruteForceSearch search({});
  std::vector<Neighbor> nn = {{}};
  search.KNearest({0, 0, 0}, 5, 1.f, &nn);
  EXPECT_TRUE(nn.empty());
  EXPECT_EQ(search.Size(), 0u);
}

}  // namespace
}  // namespace hylo::registration
