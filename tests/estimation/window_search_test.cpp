// The map filled in by the window's scans: its k nearest against a brute-force search of the
// map and of every scan's points placed by their poses.
#include "window_search.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "hylo/lie/isometry.h"
#include "hylo/mapping/ikd_tree.h"

namespace hylo::estimation {
namespace {

using registration::Neighbor;

PointCloud RandomPoints(std::mt19937* rng, int n, float half_side_m) {
  std::uniform_real_distribution<float> u(-half_side_m, half_side_m);
  PointCloud points;
  for (int i = 0; i < n; ++i) points.emplace_back(u(*rng), u(*rng), u(*rng));
  return points;
}

// The k nearest within max_distance: of the map alone where it has k, else of all the points.
std::vector<Neighbor> BruteForce(const PointCloud& map, const PointCloud& scans_in_map,
                                 const Eigen::Vector3f& query, int k, float max_distance) {
  const auto nearest = [&](const PointCloud& points) {
    std::vector<Neighbor> all;
    for (const Eigen::Vector3f& p : points) {
      const float d2 = (p - query).squaredNorm();
      if (d2 <= max_distance * max_distance) all.push_back({p, d2});
    }
    std::sort(all.begin(), all.end(), [](const Neighbor& a, const Neighbor& b) {
      return a.squared_distance < b.squared_distance;
    });
    all.resize(std::min<std::size_t>(all.size(), k));
    return all;
  };
  std::vector<Neighbor> in_map = nearest(map);
  if (static_cast<int>(in_map.size()) >= k) return in_map;
  PointCloud all = map;
  all.insert(all.end(), scans_in_map.begin(), scans_in_map.end());
  return nearest(all);
}

// Six scans of random points in their own frames, placed by random poses.
struct Window {
  explicit Window(std::mt19937* rng) : trees(6), point_lists(6) {
    for (std::size_t s = 0; s < trees.size(); ++s) {
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      const Eigen::Vector3d phi(u(*rng), u(*rng), u(*rng));
      const Eigen::Vector3d t_m(u(*rng), u(*rng), u(*rng));
      const lie::SE3d T_map_scan(lie::SO3d::Exp(0.3 * phi), t_m);
      const PointCloud points = RandomPoints(rng, 2000, 6.f);
      trees[s].Build(points);
      for (const Eigen::Vector3f& p : points) point_lists[s].push_back(p.cast<double>());
      scans.push_back({&trees[s], &point_lists[s], T_map_scan});
      const Eigen::Isometry3f T = lie::ToIsometry(T_map_scan).cast<float>();
      for (const Eigen::Vector3f& p : points) in_map.push_back(T * p);
    }
  }
  std::vector<mapping::IkdTree> trees;
  std::vector<std::vector<Eigen::Vector3d>> point_lists;
  std::vector<MapAndWindowSearch::Scan> scans;
  PointCloud in_map;  // every scan's points, map frame
};

void ExpectSameNeighbors(const std::vector<Neighbor>& found,
                         const std::vector<Neighbor>& expected) {
  ASSERT_EQ(found.size(), expected.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    EXPECT_NEAR(found[i].squared_distance, expected[i].squared_distance, 1e-4f);
    EXPECT_LT((found[i].point - expected[i].point).norm(), 1e-4f);
  }
}

TEST(MapAndWindowSearch, FindsTheKNearestOfTheMapOrOfMapAndScansTogether) {
  std::mt19937 rng(7);
  // A map over part of the volume, so that some queries find k in it and others not.
  mapping::IkdTree map;
  const PointCloud map_points = RandomPoints(&rng, 3000, 3.f);
  map.Build(map_points);
  const Window window(&rng);
  const MapAndWindowSearch search(map, window.scans);
  EXPECT_EQ(search.Size(), map_points.size() + window.in_map.size());

  int from_map_only = 0;
  std::vector<Neighbor> found;
  for (const Eigen::Vector3f& query : RandomPoints(&rng, 500, 6.f)) {
    for (const float max_distance : {0.3f, 1.f}) {
      const int k = 5;
      search.KNearest(query, k, max_distance, &found);
      ExpectSameNeighbors(found, BruteForce(map_points, window.in_map, query, k, max_distance));
      std::vector<Neighbor> in_map;
      map.KNearest(query, k, max_distance, &in_map);
      from_map_only += static_cast<int>(in_map.size()) >= k;
    }
  }
  // Both branches ran: queries the map alone answered, and queries the scans filled in.
  EXPECT_GT(from_map_only, 20);
  EXPECT_LT(from_map_only, 900);
}

TEST(MapAndWindowSearch, WithAnEmptyMapFindsTheKNearestOfAllTheScans) {
  std::mt19937 rng(8);
  const mapping::IkdTree empty_map;
  const Window window(&rng);
  const MapAndWindowSearch search(empty_map, window.scans);
  EXPECT_EQ(search.Size(), window.in_map.size());
  std::vector<Neighbor> found;
  for (const Eigen::Vector3f& query : RandomPoints(&rng, 500, 6.f)) {
    for (const int k : {1, 5, 12}) {
      search.KNearest(query, k, 1.f, &found);
      ExpectSameNeighbors(found, BruteForce({}, window.in_map, query, k, 1.f));
    }
  }
}

}  // namespace
}  // namespace hylo::estimation
