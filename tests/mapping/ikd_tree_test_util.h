#pragma once
// Helpers for the ikd-tree tests: a plain vector model of the map, and checks that a search
// index answers exactly like the brute-force reference.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "hylo/mapping/ikd_tree.h"
#include "hylo/registration/brute_force_search.h"

namespace hylo::mapping::testing {

using hylo::PointCloud;
using registration::BruteForceSearch;
using registration::Neighbor;
using registration::NeighborSearch;

inline bool LexLess(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

inline PointCloud Sorted(PointCloud points) {
  std::sort(points.begin(), points.end(), LexLess);
  return points;
}

inline bool InBox(const Box3f& box, const Eigen::Vector3f& p) {
  return (p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all();
}

/// Removes from `model` every point inside `box`; returns how many.
inline std::size_t EraseInBox(const Box3f& box, PointCloud* model) {
  const std::size_t before = model->size();
  model->erase(std::remove_if(model->begin(), model->end(),
                              [&](const Eigen::Vector3f& p) { return InBox(box, p); }),
               model->end());
  return before - model->size();
}

/// Squared distances agree within a relative tolerance (the two sides may round differently).
inline bool NearlyEqual(float a, float b) {
  return std::abs(a - b) <= 1e-5f * std::max({1e-30f, std::abs(a), std::abs(b)});
}

/// `actual` must hold the same squared distances as `expected` (nearest first). Lists may
/// differ in length only by entries lying on the max-distance boundary (rounding decides).
inline void ExpectSameNeighbors(const std::vector<Neighbor>& expected,
                                const std::vector<Neighbor>& actual, float boundary_d2,
                                const Eigen::Vector3f& query) {
  const std::size_t common = std::min(expected.size(), actual.size());
  for (std::size_t i = 0; i < common; ++i) {
    ASSERT_TRUE(NearlyEqual(expected[i].squared_distance, actual[i].squared_distance))
        << "neighbour " << i << " of query " << query.transpose() << ": expected d2 "
        << expected[i].squared_distance << ", got " << actual[i].squared_distance;
    ASSERT_TRUE(NearlyEqual((actual[i].point - query).squaredNorm(), actual[i].squared_distance))
        << "returned distance does not belong to returned point";
  }
  const std::vector<Neighbor>& longer = expected.size() > actual.size() ? expected : actual;
  for (std::size_t i = common; i < longer.size(); ++i) {
    ASSERT_TRUE(NearlyEqual(longer[i].squared_distance, boundary_d2))
        << "query " << query.transpose() << ": expected " << expected.size() << " neighbours, got "
        << actual.size();
  }
}

/// k-NN, radius and box queries of `tree` against brute force over `model`, at `queries`.
inline void ExpectMatchesModel(const IkdTree& tree, const PointCloud& model,
                               const PointCloud& queries, float max_distance) {
  std::string why;
  ASSERT_TRUE(tree.CheckInvariants(&why)) << why;
  ASSERT_EQ(tree.Size(), model.size());
  const BruteForceSearch reference(model);
  const NeighborSearch& search = tree;  // registration code sees only the interface
  std::vector<Neighbor> expected;
  std::vector<Neighbor> actual;
  for (const Eigen::Vector3f& q : queries) {
    for (int k : {1, 5, 12}) {
      reference.KNearest(q, k, max_distance, &expected);
      search.KNearest(q, k, max_distance, &actual);
      ExpectSameNeighbors(expected, actual, max_distance * max_distance, q);
    }
    reference.Radius(q, 0.5f * max_distance, &expected);
    tree.Radius(q, 0.5f * max_distance, &actual);
    ExpectSameNeighbors(expected, actual, 0.25f * max_distance * max_distance, q);
    if (::testing::Test::HasFatalFailure()) return;
  }
  const Eigen::Vector3f half = Eigen::Vector3f::Constant(0.5f * max_distance);
  for (std::size_t i = 0; i < queries.size(); i += 7) {
    const Box3f box{queries[i] - half, queries[i] + half};
    PointCloud in_tree;
    tree.BoxSearch(box, &in_tree);
    PointCloud in_model;
    for (const Eigen::Vector3f& p : model) {
      if (InBox(box, p)) in_model.push_back(p);
    }
    ASSERT_EQ(Sorted(in_tree), Sorted(in_model)) << "box search around " << queries[i].transpose();
  }
}

inline PointCloud UniformCloud(std::size_t n, float extent, std::mt19937* rng) {
  std::uniform_real_distribution<float> u(-extent, extent);
  PointCloud points(n);
  for (auto& p : points) p = {u(*rng), u(*rng), u(*rng)};
  return points;
}

}  // namespace hylo::mapping::testing
