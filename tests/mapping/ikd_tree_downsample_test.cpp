// IkdTree on-tree downsampling: every voxel keeps the one point nearest its centre, checked
// against registration::UniformSample and against a voxel-map model with box deletes.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <random>
#include <string>

#include "hylo/mapping/ikd_tree.h"
#include "hylo/registration/voxel_filter.h"
#include "ikd_tree_test_util.h"

namespace hylo::mapping {
namespace {
using namespace hylo::mapping::testing;  // NOLINT
using Key = std::array<int64_t, 3>;

Key KeyOf(const Eigen::Vector3f& p, float voxel) {
  const auto v = VoxelOf(p, voxel);
  return {v[0], v[1], v[2]};
}

// The rule written the plain way: a voxel's point changes only for a strictly nearer one.
struct VoxelModel {
  float voxel;
  std::map<Key, Eigen::Vector3f> cells;

  void Insert(const Eigen::Vector3f& p) {
    const Key key = KeyOf(p, voxel);
    const Eigen::Vector3f centre = VoxelCentre(VoxelOf(p, voxel), voxel);
    auto it = cells.find(key);
    if (it == cells.end()) {
      cells.emplace(key, p);
    } else if ((p - centre).squaredNorm() < (it->second - centre).squaredNorm()) {
      it->second = p;
    }
  }
  std::size_t EraseInBox(const Box3f& box) {
    std::size_t erased = 0;
    for (auto it = cells.begin(); it != cells.end();) {
      if (InBox(box, it->second)) {
        it = cells.erase(it);
        ++erased;
      } else {
        ++it;
      }
    }
    return erased;
  }
  PointCloud Points() const {
    PointCloud points;
    for (const auto& [key, p] : cells) points.push_back(p);
    return points;
  }
};

TEST(IkdTreeDownsample, InsertIntoEmptyTreeEqualsUniformSample) {
  std::mt19937 rng(21);
  const PointCloud cloud = UniformCloud(30000, 10.f, &rng);
  for (float voxel : {0.5f, 1.3f}) {
    IkdTree tree;
    const IkdTree::InsertSummary s = tree.Insert(cloud, voxel);
    const PointCloud expected = registration::UniformSample(cloud, voxel);
    EXPECT_EQ(Sorted(tree.Flatten()), Sorted(expected)) << "voxel " << voxel;
    EXPECT_EQ(s.num_inserted - s.num_replaced, expected.size());
    EXPECT_EQ(s.num_inserted + s.num_skipped, cloud.size());
  }
}

TEST(IkdTreeDownsample, DensePriorMapVoxelCollapsesToNearestPoint) {
  IkdTree tree;
  // Five prior points in voxel (0,0,0) of edge 1; the centre is (0.5, 0.5, 0.5).
  tree.Build({{0.1f, 0.1f, 0.1f},
              {0.4f, 0.5f, 0.5f},
              {0.9f, 0.9f, 0.9f},
              {0.2f, 0.8f, 0.3f},
              {0.45f, 0.5f, 0.5f},
              {1.5f, 0.5f, 0.5f}});
  IkdTree::InsertSummary s = tree.Insert({{0.05f, 0.95f, 0.5f}}, 1.f);  // farther than the best
  EXPECT_EQ(s.num_skipped, 1u);
  EXPECT_EQ(Sorted(tree.Flatten()), Sorted({{0.45f, 0.5f, 0.5f}, {1.5f, 0.5f, 0.5f}}));
  s = tree.Insert({{0.5f, 0.5f, 0.52f}}, 1.f);  // nearer: replaces
  EXPECT_EQ(s.num_inserted, 1u);
  EXPECT_EQ(s.num_replaced, 1u);
  EXPECT_EQ(Sorted(tree.Flatten()), Sorted({{0.5f, 0.5f, 0.52f}, {1.5f, 0.5f, 0.5f}}));
}

// Brute-force down-sampling insert into a plain set: the voxel of `p` keeps the point nearest
// its centre among its current points and `p`.
void InsertDownsampledInto(const Eigen::Vector3f& p, float voxel, PointCloud* set) {
  const auto key = VoxelOf(p, voxel);
  const Eigen::Vector3f centre = VoxelCentre(key, voxel);
  Eigen::Vector3f best = p;
  float best_d2 = std::numeric_limits<float>::infinity();
  PointCloud rest;
  for (const Eigen::Vector3f& q : *set) {
    if (VoxelOf(q, voxel) != key) {
      rest.push_back(q);
    } else if ((q - centre).squaredNorm() < best_d2) {
      best_d2 = (q - centre).squaredNorm();
      best = q;
    }
  }
  rest.push_back((p - centre).squaredNorm() < best_d2 ? p : best);
  set->swap(rest);
}

class IkdTreeVoxelCache : public ::testing::TestWithParam<int> {};

// Plain inserts, point deletes and box deletes between down-sampling inserts change voxels
// behind the tree's voxel cache: the cache must follow, and the map must match brute force,
// with no cache, a 4-voxel cache (evicting all the time) and the default one.
TEST_P(IkdTreeVoxelCache, FollowsEveryKindOfUpdate) {
  std::mt19937 rng(41);
  const float voxel = 0.5f;
  IkdTree::Options options;
  options.voxel_cache_max = GetParam();
  IkdTree tree(options);
  PointCloud truth = UniformCloud(3000, 3.f, &rng);  // several points per voxel
  tree.Build(truth);
  for (int round = 0; round < 8; ++round) {
    const PointCloud scan = UniformCloud(400, 3.f, &rng);
    tree.Insert(scan, voxel);
    for (const auto& p : scan) InsertDownsampledInto(p, voxel, &truth);
    std::string why;
    ASSERT_TRUE(tree.CheckInvariants(&why)) << "round " << round << ": " << why;
    ASSERT_EQ(Sorted(tree.Flatten()), Sorted(truth)) << "round " << round;
    // Plain inserts (duplicates included), deletes of single points, a box cutting voxels.
    const PointCloud plain = UniformCloud(200, 3.f, &rng);
    tree.Insert(plain, 0.f);
    tree.Insert({plain.front()}, 0.f);
    truth.insert(truth.end(), plain.begin(), plain.end());
    truth.push_back(plain.front());
    PointCloud removed(truth.begin(), truth.begin() + 150);
    removed.push_back(plain.front());
    tree.Delete(removed);
    PointCloud kept;
    for (const auto& q : truth) {
      if (std::find(removed.begin(), removed.end(), q) == removed.end()) kept.push_back(q);
    }
    truth.swap(kept);
    const float c = -2.f + 0.5f * static_cast<float>(round);
    const Box3f box{Eigen::Vector3f(c - 0.37f, -3.f, -1.13f),
                    Eigen::Vector3f(c + 0.71f, 3.f, 0.9f)};
    EXPECT_EQ(tree.DeleteBox(box), EraseInBox(box, &truth));
    ASSERT_TRUE(tree.CheckInvariants(&why)) << "round " << round << ": " << why;
    ASSERT_EQ(Sorted(tree.Flatten()), Sorted(truth)) << "round " << round;
  }
  // Every way of deciding must have run (cache, occupancy counts, tree searches).
  EXPECT_GT(tree.stats().num_voxel_searches, 0u);
  EXPECT_GT(tree.stats().num_voxels_proven_empty, 0u);
  if (GetParam() > 0) {
    EXPECT_GT(tree.stats().num_voxel_cache_hits, 0u);
  } else {
    EXPECT_EQ(tree.stats().num_voxel_cache_hits, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(CacheSizes, IkdTreeVoxelCache, ::testing::Values(0, 4, 1 << 16));

class IkdTreeDownsampleMix : public ::testing::TestWithParam<float> {};

// Scans drifting through space, inserted with downsampling, with a box deleted behind them:
// the tree must hold exactly the voxel model's points and answer queries like brute force.
TEST_P(IkdTreeDownsampleMix, AgreesWithVoxelModel) {
  const float scale = GetParam();  // 1 = metres; 1e-6 and 1e4 move the set to tiny/huge
  const float voxel = 0.5f * scale;
  std::mt19937 rng(33);
  IkdTree::Options options;
  options.min_checked_size = 32;
  IkdTree tree(options);
  VoxelModel model{voxel, {}};
  for (int step = 0; step < 60; ++step) {
    PointCloud scan = UniformCloud(800, 6.f * scale, &rng);
    for (auto& p : scan) p.x() += 1.5f * scale * static_cast<float>(step);
    tree.Insert(scan, voxel);
    for (const auto& p : scan) model.Insert(p);
    const float behind = (1.5f * static_cast<float>(step) - 8.f) * scale;
    const Box3f box{Eigen::Vector3f(behind - 3.f * scale, -7.f * scale, -7.f * scale),
                    Eigen::Vector3f(behind, 7.f * scale, 7.f * scale)};
    EXPECT_EQ(tree.DeleteBox(box), model.EraseInBox(box));
    if (step % 10 == 9) {
      std::string why;
      ASSERT_TRUE(tree.CheckInvariants(&why)) << "step " << step << ": " << why;
      const PointCloud points = model.Points();
      ASSERT_EQ(Sorted(tree.Flatten()), Sorted(points)) << "step " << step;
      PointCloud queries = UniformCloud(80, 7.f * scale, &rng);
      for (auto& q : queries) q.x() += 1.5f * scale * static_cast<float>(step);
      ExpectMatchesModel(tree, points, queries, 2.f * scale);
    }
    if (HasFatalFailure()) return;
  }
}

INSTANTIATE_TEST_SUITE_P(Scales, IkdTreeDownsampleMix, ::testing::Values(1.f, 1e-6f, 1e4f));

}  // namespace
}  // namespace hylo::mapping
