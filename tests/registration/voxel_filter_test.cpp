#include "hylo/common/check.h"
#include "hylo/registration/voxel_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <tuple>

namespace hylo::registration {
namespace {

TEST(UniformSample, KeepsThePointNearestEachVoxelCentre) {
  // Two points in voxel [0,1)^3: the one nearer (0.5,0.5,0.5) must survive.
  const PointCloud cloud = {{0.1f, 0.1f, 0.1f}, {0.45f, 0.55f, 0.5f}, {1.5f, 0.5f, 0.5f}};
  const PointCloud out = UniformSample(cloud, 1.0f);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(out[0].isApprox(Eigen::Vector3f(0.45f, 0.55f, 0.5f)));
  EXPECT_TRUE(out[1].isApprox(Eigen::Vector3f(1.5f, 0.5f, 0.5f)));
}

TEST(UniformSample, NegativeCoordinatesUseFloorNotTruncation) {
  // -0.2 and +0.2 lie in different voxels of edge 1 m ([-1,0) and [0,1)).
  const PointCloud out = UniformSample({{-0.2f, 0.f, 0.f}, {0.2f, 0.f, 0.f}}, 1.0f);
  EXPECT_EQ(out.size(), 2u);
}

TEST(UniformSample, OnePointPerOccupiedVoxelOnRandomCloud) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-5.f, 5.f);
  PointCloud cloud(20000);
  for (auto& p : cloud) p = {u(rng), u(rng), u(rng)};
  const float voxel = 0.7f;
  const PointCloud out = UniformSample(cloud, voxel);
  std::set<std::tuple<int, int, int>> occupied, kept;
  auto key = [&](const Eigen::Vector3f& p) {
    return std::make_tuple(int(std::floor(p.x() / voxel)), int(std::floor(p.y() / voxel)),
                           int(std::floor(p.z() / voxel)));
  };
  for (const auto& p : cloud) occupied.insert(key(p));
  for (const auto& p : out) EXPECT_TRUE(kept.insert(key(p)).second) << "two points in a voxel";
  EXPECT_EQ(kept, occupied);
}

TEST(UniformSample, NonPositiveVoxelReturnsInput) {
  const PointCloud cloud = {{1, 2, 3}, {1, 2, 3}};
  EXPECT_EQ(UniformSample(cloud, 0.f).size(), 2u);
  EXPECT_TRUE(UniformSample({}, 0.5f).empty());
}

TEST(UniformSampler, StreamEqualsUniformSampleOfEverythingAdded) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-3.f, 3.f);
  PointCloud all;
  UniformSampler sampler(0.25f);
  for (int chunk = 0; chunk < 5; ++chunk) {  // overlapping chunks: later points replace earlier
    PointCloud part(3000);
    for (auto& p : part) p = {u(rng), u(rng), 0.3f * u(rng)};
    all.insert(all.end(), part.begin(), part.end());
    EXPECT_EQ(sampler.Add(part), 0u);
    const PointCloud expected = UniformSample(all, 0.25f);
    ASSERT_EQ(sampler.points().size(), expected.size()) << "after chunk " << chunk;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      ASSERT_EQ(sampler.points()[i], expected[i]) << "point " << i << " after chunk " << chunk;
    }
  }
  EXPECT_GT(sampler.MemoryBytes(), sampler.points().size() * sizeof(Eigen::Vector3f));
}

TEST(UniformSampler, SkipsAndCountsUnusablePoints) {
  UniformSampler sampler(0.1f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(sampler.Add({{0.f, 0.f, 0.f}, {nan, 0.f, 0.f}, {0.f, inf, 0.f}, {3e8f, 0.f, 0.f}}),
            3u);
  ASSERT_EQ(sampler.points().size(), 1u);
  EXPECT_EQ(sampler.points()[0], Eigen::Vector3f::Zero());
}

TEST(UniformSampler, RejectsANonPositiveOrNonFiniteVoxel) {
  EXPECT_THROW(UniformSampler(0.f), InternalError);
  EXPECT_THROW(UniformSampler(-0.1f), InternalError);
  EXPECT_THROW(UniformSampler{std::numeric_limits<float>::quiet_NaN()}, InternalError);
}

}  // namespace
}  // namespace hylo::registration
