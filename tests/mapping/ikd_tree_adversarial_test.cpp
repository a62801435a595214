// IkdTree on adversarial point sets: duplicates, collinear and coplanar points, huge (~1e6)
// and tiny (~1e-6) coordinates. Each set goes through a build, incremental inserts, point and
// box deletes, and must agree with brute force at every check.

#include <gtest/gtest.h>

#include <random>

#include "hylo/mapping/ikd_tree.h"
#include "ikd_tree_test_util.h"

namespace hylo::mapping {
namespace {
using namespace hylo::mapping::testing;  // NOLINT

struct AdversarialSet {
  const char* name;
  PointCloud (*make)(std::size_t n, std::mt19937* rng);
  float scale;  // typical spacing of the set, m: sets query radii and box sizes
};

PointCloud Duplicates(std::size_t n, std::mt19937* rng) {
  PointCloud points(n / 2, Eigen::Vector3f(1.f, 2.f, 3.f));  // half the set is one point
  std::uniform_int_distribution<int> cell(-3, 3);            // the rest on a coarse grid
  for (std::size_t i = points.size(); i < n; ++i) {
    points.emplace_back(cell(*rng), cell(*rng), cell(*rng));
  }
  return points;
}

PointCloud Collinear(std::size_t n, std::mt19937* rng) {
  std::uniform_real_distribution<float> t(-50.f, 50.f);
  const Eigen::Vector3f direction = Eigen::Vector3f(1.f, -2.f, 0.5f).normalized();
  PointCloud points;
  for (std::size_t i = 0; i < n; ++i)
    points.push_back(Eigen::Vector3f(3, 1, 2) + t(*rng) * direction);
  return points;
}

PointCloud Coplanar(std::size_t n, std::mt19937* rng) {
  std::uniform_real_distribution<float> u(-30.f, 30.f);
  PointCloud points;
  for (std::size_t i = 0; i < n; ++i) points.emplace_back(u(*rng), u(*rng), 0.f);
  return points;
}

// UTM-sized coordinates left in float (what local_origin.h exists to avoid): spacing 0.0625 m,
// so many points coincide and many distances tie.
PointCloud Huge(std::size_t n, std::mt19937* rng) {
  std::uniform_real_distribution<float> u(-200.f, 200.f);
  PointCloud points;
  for (std::size_t i = 0; i < n; ++i) {
    points.emplace_back(1e6f + u(*rng), -1e6f + u(*rng), 5e5f + 0.1f * u(*rng));
  }
  return points;
}

PointCloud Tiny(std::size_t n, std::mt19937* rng) {
  std::uniform_real_distribution<float> u(-1e-6f, 1e-6f);
  PointCloud points;
  for (std::size_t i = 0; i < n; ++i) points.emplace_back(u(*rng), u(*rng), u(*rng));
  return points;
}

class IkdTreeAdversarial : public ::testing::TestWithParam<AdversarialSet> {};

TEST_P(IkdTreeAdversarial, BuildThenMixedUpdatesMatchBruteForce) {
  const AdversarialSet& set = GetParam();
  std::mt19937 rng(11);
  IkdTree::Options options;
  options.min_checked_size = 16;  // rebuild often
  IkdTree tree(options);
  PointCloud model = set.make(4000, &rng);
  tree.Build(model);
  ExpectMatchesModel(tree, model, set.make(100, &rng), 3.f * set.scale);
  for (int round = 0; round < 30; ++round) {
    const PointCloud batch = set.make(300, &rng);
    tree.Insert(batch);
    model.insert(model.end(), batch.begin(), batch.end());
    const PointCloud victims = {model[rng() % model.size()], model[rng() % model.size()]};
    std::size_t expected = 0;
    for (const Eigen::Vector3f& v : Sorted(victims)) {
      const std::size_t before = model.size();
      model.erase(std::remove(model.begin(), model.end(), v), model.end());
      expected += before - model.size();
    }
    EXPECT_EQ(tree.Delete(victims), expected);
    const Eigen::Vector3f centre =
        model.empty() ? Eigen::Vector3f::Zero() : model[rng() % model.size()];
    const Eigen::Vector3f half = Eigen::Vector3f::Constant(4.f * set.scale);
    const Box3f box{centre - half, centre + half};
    EXPECT_EQ(tree.DeleteBox(box), EraseInBox(box, &model));
    if (round % 5 == 4) {
      ExpectMatchesModel(tree, model, set.make(60, &rng), 3.f * set.scale);
      ASSERT_EQ(Sorted(tree.Flatten()), Sorted(model)) << set.name << " round " << round;
    }
    if (HasFatalFailure()) return;
  }
  // Balance holds even when every split coordinate ties: depth stays logarithmic.
  EXPECT_LE(tree.Depth(), 40) << set.name;
}

TEST_P(IkdTreeAdversarial, IncrementalInsertFromEmptyMatchesBruteForce) {
  const AdversarialSet& set = GetParam();
  std::mt19937 rng(5);
  IkdTree tree;
  PointCloud model;
  for (int round = 0; round < 20; ++round) {
    const PointCloud batch = set.make(500, &rng);
    tree.Insert(batch);
    model.insert(model.end(), batch.begin(), batch.end());
  }
  ExpectMatchesModel(tree, model, set.make(150, &rng), 3.f * set.scale);
  EXPECT_LE(tree.Depth(), 40) << set.name;
}

INSTANTIATE_TEST_SUITE_P(Sets, IkdTreeAdversarial,
                         ::testing::Values(AdversarialSet{"duplicates", Duplicates, 1.f},
                                           AdversarialSet{"collinear", Collinear, 1.f},
                                           AdversarialSet{"coplanar", Coplanar, 1.f},
                                           AdversarialSet{"huge", Huge, 5.f},
                                           AdversarialSet{"tiny", Tiny, 1e-7f}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(IkdTreeAdversarial, DeletingADuplicatedPointRemovesEveryCopy) {
  IkdTree tree;
  PointCloud cloud(1000, Eigen::Vector3f(1, 1, 1));
  cloud.push_back({2, 2, 2});
  tree.Insert(cloud);
  EXPECT_EQ(tree.Delete({{1, 1, 1}}), 1000u);
  EXPECT_EQ(tree.Size(), 1u);
  std::vector<registration::Neighbor> nn;
  tree.KNearest({1, 1, 1}, 5, 10.f, &nn);
  ASSERT_EQ(nn.size(), 1u);
  EXPECT_EQ(nn[0].point, Eigen::Vector3f(2, 2, 2));
}

}  // namespace
}  // namespace hylo::mapping
