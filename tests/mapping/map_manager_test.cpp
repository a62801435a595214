// The map manager: merged queries equal brute force over prior ∪ run points; the local window
// deletes far run points and never a prior point.
#include "hylo/mapping/map_manager.h"

#include <gtest/gtest.h>

#include <random>

#include "hylo/registration/brute_force_search.h"

namespace hylo::mapping {
namespace {

using hylo::PointCloud;

PointCloud RandomCloud(int n, const Eigen::Vector3f& centre, float half, std::mt19937* rng) {
  std::uniform_real_distribution<float> u(-half, half);
  PointCloud points;
  for (int i = 0; i < n; ++i) points.push_back(centre + Eigen::Vector3f(u(*rng), u(*rng), u(*rng)));
  return points;
}

TEST(MapManager, MergedNearestNeighboursEqualBruteForce) {
  std::mt19937 rng(5);
  MapManagerOptions options;
  options.voxel_size_m = 0.01f;
  MapManager map(options);
  const PointCloud prior = RandomCloud(3000, Eigen::Vector3f::Zero(), 10.f, &rng);
  const PointCloud run = RandomCloud(3000, Eigen::Vector3f(3, 0, 0), 10.f, &rng);
  map.SetPrior(prior);
  map.AddScan(run, Eigen::Vector3f::Zero());
  PointCloud all = prior;
  const PointCloud stored_run = map.FlattenRun();
  all.insert(all.end(), stored_run.begin(), stored_run.end());
  const registration::BruteForceSearch reference(all);
  ASSERT_EQ(map.Size(), all.size());
  std::vector<registration::Neighbor> got, want;
  for (const Eigen::Vector3f& q : RandomCloud(200, Eigen::Vector3f::Zero(), 12.f, &rng)) {
    map.KNearest(q, 5, 3.f, &got);
    reference.KNearest(q, 5, 3.f, &want);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_FLOAT_EQ(got[i].squared_distance, want[i].squared_distance);
    }
  }
}

TEST(MapManager, WindowDeletesFarRunPointsButNeverPriorPoints) {
  std::mt19937 rng(6);
  MapManagerOptions options;
  options.voxel_size_m = 0.05f;
  options.window_size_m = 40.f;
  options.window_margin_m = 10.f;
  MapManager map(options);
  const PointCloud prior = RandomCloud(2000, Eigen::Vector3f::Zero(), 15.f, &rng);
  map.SetPrior(prior);
  map.AddScan(RandomCloud(2000, Eigen::Vector3f::Zero(), 15.f, &rng), Eigen::Vector3f::Zero());
  const std::size_t run_before = map.run_size();
  // Drive 60 m along x, adding points around the vehicle.
  for (float x = 5.f; x <= 60.f; x += 5.f) {
    map.AddScan(RandomCloud(200, Eigen::Vector3f(x, 0, 0), 5.f, &rng), Eigen::Vector3f(x, 0, 0));
  }
  EXPECT_GT(map.counters().window_moves, 0u);
  EXPECT_GT(map.counters().points_windowed_out, run_before / 2);
  EXPECT_EQ(map.prior_size(), prior.size());  // every prior point survives
  for (const Eigen::Vector3f& p : map.FlattenRun()) {
    EXPECT_GE(p.x(), map.window().min.x());
  }
}

TEST(MapManagerOptions, NamesTheBrokenField) {
  MapManagerOptions o;
  o.window_margin_m = 200.f;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("window_margin_m"), std::string::npos);
}

}  // namespace
}  // namespace hylo::mapping
