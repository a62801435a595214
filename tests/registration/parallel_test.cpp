#include "hylo/registration/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <random>
#include <stdexcept>
#include <vector>

#include "hylo/registration/voxel_filter.h"

namespace hylo::registration {
namespace {

TEST(ParallelFor, CoversEveryItemOnceAtAnyThreadCount) {
  for (const int threads : {1, 2, 3, 4}) {
    const ThreadLimit limit(threads);
    for (const std::size_t n :
         {std::size_t{0}, std::size_t{1}, std::size_t{511}, std::size_t{100003}}) {
      std::vector<int> visits(n, 0);
      limit.Run([&] {
        ParallelFor(n, [&](std::size_t begin, std::size_t end) {
          ASSERT_LE(begin, end);
          ASSERT_LE(end, n);
          for (std::size_t i = begin; i < end; ++i) ++visits[i];
        });
      });
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(visits[i], 1) << "item " << i << " of " << n << " at " << threads << " threads";
      }
    }
  }
}

TEST(ParallelFor, UsesMoreThanOneThreadOnlyInsideRun) {
  EXPECT_EQ(ParallelThreads(), 1);
  const ThreadLimit limit(2);
  EXPECT_GE(limit.threads(), 1);
  EXPECT_LE(limit.threads(), 2);  // no more than the machine's cores
  limit.Run([&] { EXPECT_EQ(ParallelThreads(), limit.threads()); });
  EXPECT_EQ(ParallelThreads(), 1);
  // Outside Run a loop is one call on the calling thread.
  int calls = 0;
  ParallelFor(100000, [&](std::size_t begin, std::size_t end) {
    ++calls;
    EXPECT_EQ(begin, 0u);
    EXPECT_EQ(end, 100000u);
  });
  EXPECT_EQ(calls, 1);
  EXPECT_GE(ThreadLimit(0).threads(), 1);  // every core
}

TEST(ParallelFor, AnErrorInsideRunReachesTheCallerAndRestoresTheLimit) {
  const ThreadLimit limit(2);
  EXPECT_THROW(limit.Run([] { throw std::runtime_error("bad scan"); }), std::runtime_error);
  EXPECT_EQ(ParallelThreads(), 1);
  std::atomic<int> items{0};
  limit.Run([&] {
    ParallelFor(
        4096, [&](std::size_t begin, std::size_t end) { items += static_cast<int>(end - begin); });
  });
  EXPECT_EQ(items.load(), 4096);
}

TEST(ParallelTasks, RunsEachTaskOnce) {
  const ThreadLimit limit(4);
  std::vector<int> runs(7, 0);
  limit.Run([&] { ParallelTasks(7, [&](int t) { ++runs[static_cast<std::size_t>(t)]; }); });
  EXPECT_EQ(runs, std::vector<int>(7, 1));
}

// The sampled indices split over parts are the serial ones exactly: same points, same order,
// the same point kept on a tie (many points at one distance from their voxel's centre).
TEST(UniformSampleIndices, TheSameOnAnyNumberOfThreads) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-20.f, 20.f);
  std::uniform_int_distribution<int> lattice(-40, 40);
  PointCloud cloud(60000);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    // Every third point on a 0.25 m lattice: ties for the voxel's nearest point.
    cloud[i] = i % 3 == 0 ? Eigen::Vector3f(0.25f * lattice(rng), 0.25f * lattice(rng),
                                            0.25f * lattice(rng))
                          : Eigen::Vector3f(u(rng), u(rng), u(rng));
  }
  for (const float voxel : {0.5f, 2.0f}) {
    const std::vector<std::size_t> serial = UniformSampleIndices(cloud, voxel);
    ASSERT_GT(serial.size(), 1000u);
    for (const int threads : {2, 3, 4}) {
      std::vector<std::size_t> parallel;
      ThreadLimit(threads).Run([&] { parallel = UniformSampleIndices(cloud, voxel); });
      EXPECT_EQ(parallel, serial) << threads << " threads, voxel " << voxel << " m";
    }
  }
}

}  // namespace
}  // namespace hylo::registration
