#include "hylo/localization/moving_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace hylo::localization {
namespace {

// A sweep of a few thousand points on a ring of walls around the vehicle, 5-70 m away (IMU
// frame): some beyond the search's keep radius from the start, all distinct per scan.
PointCloud Sweep(int scan) {
  PointCloud points;
  for (int i = 0; i < 3000; ++i) {
    const double azimuth = 2.0 * M_PI * i / 3000.0 + 0.001 * scan;
    const double range = 5.0 + 65.0 * ((i * 37 + scan * 11) % 100) / 100.0;
    points.emplace_back(static_cast<float>(range * std::cos(azimuth)),
                        static_cast<float>(range * std::sin(azimuth)),
                        static_cast<float>(0.5 * std::sin(0.1 * i)));
  }
  return points;
}

Eigen::Isometry3d PoseAt(int scan) {  // 1 m per scan along x, turning slowly
  Eigen::Isometry3d T_search_imu = Eigen::Isometry3d::Identity();
  T_search_imu.translation() = Eigen::Vector3d(1.0 * scan, 0.1 * scan, 0.0);
  T_search_imu.linear() = Eigen::AngleAxisd(0.02 * scan, Eigen::Vector3d::UnitZ()).matrix();
  return T_search_imu;
}

struct Taken {
  std::vector<AttemptClouds> attempts;
  std::vector<int> due_at;
};

// Runs a search over `scans` sweeps, taking an attempt's clouds whenever one is due.
Taken Search(bool accumulate_on_worker, int scans) {
  MovingSearchOptions options;
  options.retry_m = 5.0;
  MovingSearch search(options, mapping::MapManagerOptions(), registration::PlaneMatcherOptions(),
                      /*keep_radius_m=*/40.0, /*recent_scans=*/3, accumulate_on_worker);
  search.Begin(Sweep(0), PoseAt(0));
  Taken taken;
  for (int scan = 1; scan <= scans; ++scan) {
    const bool due = search.Add([scan] { return Sweep(scan); }, PointCloud(), PoseAt(scan),
                                /*first_attempt_scans=*/0);
    if (!due) continue;
    taken.due_at.push_back(scan);
    taken.attempts.push_back(search.TakeAttemptClouds(PoseAt(scan)).get());
  }
  return taken;
}

// The clouds an attempt looks at are the same whether the scans are accumulated on the
// search's own thread or on the caller's, and they are what the search promises: the
// accumulated cloud within the keep radius of the vehicle, the last scans alone, both in the
// vehicle's frame at the attempt.
TEST(MovingSearch, AttemptsSeeTheSameCloudsWhereverTheScansAreAccumulated) {
  const Taken inline_taken = Search(/*accumulate_on_worker=*/false, 30);
  const Taken worker_taken = Search(/*accumulate_on_worker=*/true, 30);
  ASSERT_EQ(inline_taken.due_at, worker_taken.due_at);
  ASSERT_GE(inline_taken.attempts.size(), 4u);
  for (std::size_t a = 0; a < inline_taken.attempts.size(); ++a) {
    const AttemptClouds& x = inline_taken.attempts[a];
    const AttemptClouds& y = worker_taken.attempts[a];
    EXPECT_EQ(x.accumulated.points, y.accumulated.points) << "attempt " << a;
    EXPECT_EQ(x.recent.points, y.recent.points) << "attempt " << a;
    EXPECT_TRUE(x.accumulated.T_attempt_from.isApprox(y.accumulated.T_attempt_from));

    const int scan = inline_taken.due_at[a];
    const PointCloud accumulated_imu = x.accumulated.Resolve();
    ASSERT_FALSE(accumulated_imu.empty());
    for (const Eigen::Vector3f& p : accumulated_imu) ASSERT_LE(p.norm(), 40.0f + 1e-3f);
    // The recent cloud is the last three sweeps, each moved from its pose to this one.
    std::size_t recent_points = 0;
    for (int s = scan - 2; s <= scan; ++s) recent_points += Sweep(s).size();
    ASSERT_EQ(x.recent.points.size(), recent_points);
    const Eigen::Vector3f first_of_this_scan =
        x.recent.Resolve()[recent_points - Sweep(scan).size()];
    EXPECT_LT((first_of_this_scan - Sweep(scan).front()).norm(), 1e-4f);
  }
}

}  // namespace
}  // namespace hylo::localization
