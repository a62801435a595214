// IkdTree against brute force: after builds, after long random mixes of inserts, point
// deletes and box deletes (with rebuilds forced often), and with on-tree downsampling
// against a voxel-map model.

#include "hylo/mapping/ikd_tree.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <thread>

#include "hylo/common/check.h"
#include "hylo/registration/voxel_filter.h"
#include "ikd_tree_test_util.h"

namespace hylo::mapping {
namespace {
using namespace hylo::mapping::testing;  // NOLINT

TEST(IkdTreeOptions, IsValidNamesTheBrokenField) {
  std::string why;
  EXPECT_TRUE(IkdTree::Options().IsValid(&why)) << why;
  IkdTree::Options options;
  options.alpha_balance = 0.5f;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("alpha_balance"), std::string::npos) << why;
  options = IkdTree::Options();
  options.leaf_size = IkdTree::kBucketCapacity + 1;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("leaf_size"), std::string::npos) << why;
  options = IkdTree::Options();
  options.voxel_cache_max = 3;  // less than one set
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("voxel_cache_max"), std::string::npos) << why;
  options.leaf_size = IkdTree::kBucketCapacity + 1;
  EXPECT_THROW(IkdTree{options}, InternalError);
}

TEST(IkdTree, EmptyTreeAnswersNothing) {
  IkdTree tree;
  std::vector<registration::Neighbor> nn = {{}};
  tree.KNearest({0, 0, 0}, 5, 100.f, &nn);
  EXPECT_TRUE(nn.empty());
  EXPECT_EQ(tree.Size(), 0u);
  EXPECT_EQ(tree.DeleteBox({{-1, -1, -1}, {1, 1, 1}}), 0u);
  EXPECT_TRUE(tree.Flatten().empty());
}

// Regression: a box covering the whole map labels only the root; queries must not descend
// into its (stale) children.
TEST(IkdTree, DeletingEverythingByBoxLeavesNothingToFind) {
  std::mt19937 rng(2);
  IkdTree tree;
  tree.Build(UniformCloud(5000, 10.f, &rng));
  EXPECT_EQ(tree.DeleteBox({{-10, -10, -10}, {10, 10, 10}}), 5000u);
  std::vector<registration::Neighbor> nn;
  tree.KNearest({0, 0, 0}, 5, 100.f, &nn);
  EXPECT_TRUE(nn.empty());
  tree.Radius({0, 0, 0}, 100.f, &nn);
  EXPECT_TRUE(nn.empty());
  EXPECT_EQ(tree.Size(), 0u);
  tree.Insert({{1, 1, 1}});
  tree.KNearest({0, 0, 0}, 5, 100.f, &nn);
  ASSERT_EQ(nn.size(), 1u);
  EXPECT_EQ(nn[0].point, Eigen::Vector3f(1, 1, 1));
}

// The documented contract: const searches may run concurrently (no hidden mutable state).
TEST(IkdTree, ConcurrentConstQueriesAgreeWithBruteForce) {
  std::mt19937 rng(4);
  PointCloud model = UniformCloud(20000, 30.f, &rng);
  IkdTree tree;
  tree.Insert(model, 0.f);  // incrementally built: leaf splits and rebuilds have happened
  tree.DeleteBox({{-30, -30, -30}, {0, 0, 30}});
  EraseInBox({{-30, -30, -30}, {0, 0, 30}}, &model);
  const PointCloud queries = UniformCloud(2000, 32.f, &rng);
  const BruteForceSearch reference(model);
  std::vector<std::vector<registration::Neighbor>> expected(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) {
    reference.KNearest(queries[i], 5, 3.f, &expected[i]);
  }
  std::vector<int> mismatches(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      std::vector<registration::Neighbor> nn;
      for (std::size_t i = t; i < queries.size(); i += 4) {
        tree.KNearest(queries[i], 5, 3.f, &nn);
        bool same = nn.size() == expected[i].size();
        for (std::size_t j = 0; same && j < nn.size(); ++j) {
          same = NearlyEqual(nn[j].squared_distance, expected[i][j].squared_distance);
        }
        mismatches[t] += !same;
      }
    });
  }
  for (auto& thread : threads) thread.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(mismatches[t], 0) << "thread " << t;
}

TEST(IkdTree, BuildMatchesBruteForce) {
  std::mt19937 rng(1);
  const PointCloud cloud = UniformCloud(20000, 50.f, &rng);
  IkdTree tree;
  tree.Build(cloud);
  EXPECT_EQ(Sorted(tree.Flatten()), Sorted(cloud));
  ExpectMatchesModel(tree, cloud, UniformCloud(300, 55.f, &rng), 6.f);
  // A median split over 20000 points into leaves of <= 24: depth ceil(log2(20000 / 24)) + 1.
  EXPECT_LE(tree.Depth(), 11);
}

TEST(IkdTree, RejectsNonFinitePoints) {
  IkdTree tree;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const IkdTree::InsertSummary s = tree.Insert({{0, 0, 0}, {nan, 0, 0}, {1, 2, 3}});
  EXPECT_EQ(s.num_inserted, 2u);
  EXPECT_EQ(s.num_nonfinite, 1u);
  EXPECT_EQ(tree.Size(), 2u);
}

struct MixCase {
  const char* name;
  IkdTree::Options options;
};

class IkdTreeRandomMix : public ::testing::TestWithParam<MixCase> {};

// Many rounds of insert batches, point deletes (existing and absent points) and box deletes;
// the tree must agree with a vector model after every round.
TEST_P(IkdTreeRandomMix, AgreesWithBruteForceAfterEveryRound) {
  std::mt19937 rng(7);
  IkdTree tree(GetParam().options);
  PointCloud model = UniformCloud(3000, 20.f, &rng);
  tree.Build(model);
  std::uniform_real_distribution<float> u(-20.f, 20.f);
  std::uniform_real_distribution<float> side(0.5f, 8.f);
  for (int round = 0; round < 120; ++round) {
    // Inserts drift along x so the tree grows lopsided and the balance criterion fires.
    PointCloud batch = UniformCloud(150, 5.f, &rng);
    for (auto& p : batch) p.x() += 0.3f * static_cast<float>(round);
    EXPECT_EQ(tree.Insert(batch).num_inserted, batch.size());
    model.insert(model.end(), batch.begin(), batch.end());
    PointCloud to_delete;
    for (int i = 0; i < 40 && !model.empty(); ++i) to_delete.push_back(model[rng() % model.size()]);
    to_delete.push_back({100.f, 100.f, 100.f});  // absent
    std::size_t expected_deleted = 0;
    for (const auto& p : Sorted(to_delete)) {
      const auto equal = [&](const Eigen::Vector3f& q) { return q == p; };
      const std::size_t before = model.size();
      model.erase(std::remove_if(model.begin(), model.end(), equal), model.end());
      expected_deleted += before - model.size();
    }
    EXPECT_EQ(tree.Delete(to_delete), expected_deleted);
    const Eigen::Vector3f c(u(rng) + 0.3f * round, u(rng), u(rng));
    const Eigen::Vector3f h(side(rng), side(rng), side(rng));
    const Box3f box{c - h, c + h};
    EXPECT_EQ(tree.DeleteBox(box), EraseInBox(box, &model));
    if (round % 10 == 9) {
      ExpectMatchesModel(tree, model, UniformCloud(60, 25.f, &rng), 4.f);
      ASSERT_EQ(Sorted(tree.Flatten()), Sorted(model)) << "round " << round;
    }
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(tree.stats().num_rebuilds, 0u) << "the mix must exercise partial rebuilds";
}

IkdTree::Options Opts(float alpha_bal, float alpha_del, int leaf, int min_checked) {
  IkdTree::Options o;
  o.alpha_balance = alpha_bal;
  o.alpha_delete = alpha_del;
  o.leaf_size = leaf;
  o.min_checked_size = min_checked;
  return o;
}

INSTANTIATE_TEST_SUITE_P(Options, IkdTreeRandomMix,
                         ::testing::Values(MixCase{"defaults", IkdTree::Options()},
                                           MixCase{"eager_rebuilds", Opts(0.55f, 0.1f, 4, 2)},
                                           MixCase{"lazy_rebuilds", Opts(0.95f, 0.95f, 16, 512)},
                                           MixCase{"single_point_leaves", Opts(0.7f, 0.5f, 1, 8)}),
                         [](const auto& info) { return std::string(info.param.name); });

// A box that swallows whole subtrees only labels them; inserting into the labelled region
// afterwards must push the label down and leave exactly the new points there.
TEST(IkdTree, LazyBoxLabelThenInsertInside) {
  std::mt19937 rng(3);
  PointCloud model = UniformCloud(5000, 10.f, &rng);
  IkdTree tree;
  tree.Build(model);
  const Box3f box{{-10.f, -10.f, -10.f}, {0.f, 10.f, 10.f}};
  EXPECT_EQ(tree.DeleteBox(box), EraseInBox(box, &model));
  PointCloud inside = UniformCloud(500, 4.f, &rng);
  for (auto& p : inside) p.x() -= 5.f;
  tree.Insert(inside);
  model.insert(model.end(), inside.begin(), inside.end());
  ExpectMatchesModel(tree, model, UniformCloud(200, 11.f, &rng), 3.f);
  EXPECT_EQ(Sorted(tree.Flatten()), Sorted(model));
}

TEST(IkdTree, SortedInsertionStaysBalanced) {
  IkdTree tree;
  PointCloud line;
  for (int i = 0; i < 20000; ++i) line.push_back({0.01f * i, 0.f, 0.f});
  tree.Insert(line);
  EXPECT_EQ(tree.Size(), line.size());
  // alpha_bal = 0.7 bounds the depth by log_{1/0.7}(n / leaf) plus the unchecked small
  // subtrees: ~ 30; a degenerate (list-like) tree would be ~1000 deep.
  EXPECT_LE(tree.Depth(), 40);
  EXPECT_GT(tree.stats().num_rebuilds, 0u);
}

}  // namespace
}  // namespace hylo::mapping
