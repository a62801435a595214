// The 3-D DDA against brute force (dense sampling of the segment and exact segment-box tests),
// and the occupancy grid's inflation against its stated clearance band.
#include "hylo/inspection/ray_caster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <vector>

namespace hylo::inspection {
namespace {

using Key = std::array<int, 3>;
Key KeyOf(const Eigen::Vector3i& v) { return {v.x(), v.y(), v.z()}; }

// An empty grid covering [lo, hi] (no point: geometry only).
OccupancyGrid EmptyGrid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double voxel) {
  OccupancyOptions o;
  o.voxel_size_m = voxel;
  o.clearance_m = 0.0;
  return OccupancyGrid::Build({}, lo, hi, o);
}

// Length of the part of segment a-b (voxel coordinates) inside voxel v's closed box; negative
// when they do not meet.
double OverlapLength(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3i& v) {
  double t0 = 0.0, t1 = 1.0;
  const Eigen::Vector3d d = b - a;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (a[i] < v[i] || a[i] > v[i] + 1) return -1.0;
      continue;
    }
    double lo = (v[i] - a[i]) / d[i], hi = (v[i] + 1 - a[i]) / d[i];
    if (lo > hi) std::swap(lo, hi);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, hi);
  }
  return t1 < t0 ? -1.0 : (t1 - t0) * d.norm();
}

std::vector<Eigen::Vector3i> Walk(const OccupancyGrid& g, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b) {
  std::vector<Eigen::Vector3i> out;
  WalkVoxels(g, a, b, [&](const Eigen::Vector3i& v) {
    out.push_back(v);
    return false;
  });
  return out;
}

TEST(WalkVoxels, VisitsExactlyTheVoxelsTheSegmentCrossesInOrder) {
  std::mt19937 rng(7);
  const Eigen::Vector3d lo(-2.0, -1.5, -0.5), hi(3.0, 2.5, 1.7);
  const OccupancyGrid g = EmptyGrid(lo, hi, 0.1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Ends inside and well outside the grid, long and short, some along an axis.
  for (int trial = 0; trial < 250; ++trial) {
    Eigen::Vector3d a, b;
    for (int i = 0; i < 3; ++i) {
      const double span = hi[i] - lo[i] + 2.0;
      a[i] = lo[i] - 1.0 + span * u(rng);
      b[i] = trial % 5 == 0 && i != trial % 3 ? a[i] : lo[i] - 1.0 + span * u(rng);
    }
    if (trial % 7 == 0) b = a + 0.03 * (b - a);  // within a voxel or two
    SCOPED_TRACE(trial);
    const std::vector<Eigen::Vector3i> visited = Walk(g, a, b);
    const Eigen::Vector3d qa = g.ToVoxelCoordinates(a), qb = g.ToVoxelCoordinates(b);
    std::set<Key> seen;
    for (std::size_t k = 0; k < visited.size(); ++k) {
      ASSERT_TRUE(g.Contains(visited[k]));
      EXPECT_GE(OverlapLength(qa, qb, visited[k]), -1e-9) << "visited a voxel it does not meet";
      EXPECT_TRUE(seen.insert(KeyOf(visited[k])).second) << "visited twice";
      if (k > 0) {
        EXPECT_EQ((visited[k] - visited[k - 1]).cwiseAbs().sum(), 1) << "not a face step";
      }
    }
    // Every voxel a dense sampling of the segment falls in is visited.
    const int samples = 10000;
    for (int s = 0; s <= samples; ++s) {
      const Eigen::Vector3d q = qa + (qb - qa) * (double(s) / samples);
      const Eigen::Vector3i v = q.array().floor().cast<int>();
      if (g.Contains(v)) {
        EXPECT_TRUE(seen.count(KeyOf(v))) << "missed " << v.transpose();
      }
    }
  }
}

TEST(SegmentBlocked, AgreesWithBruteForceOverEveryOccupiedVoxel) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> up(0.f, 2.f);
  PointCloud points(60);
  for (auto& p : points) p = {up(rng), up(rng), up(rng)};
  OccupancyOptions o;
  o.voxel_size_m = 0.2;
  o.clearance_m = 0.0;  // blocked = occupied
  const OccupancyGrid g = OccupancyGrid::Build(points, Eigen::Vector3d::Zero(),
                                               Eigen::Vector3d::Constant(2.0), o);
  ASSERT_EQ(g.summary().blocked_voxels, g.summary().occupied_voxels);
  std::vector<Eigen::Vector3i> occupied;
  for (int z = 0; z < g.dims().z(); ++z)
    for (int y = 0; y < g.dims().y(); ++y)
      for (int x = 0; x < g.dims().x(); ++x)
        if (g.Blocked({x, y, z})) occupied.emplace_back(x, y, z);
  std::uniform_real_distribution<double> u(-0.5, 2.5);
  int blocked = 0, decided = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    const Eigen::Vector3d qa = g.ToVoxelCoordinates(a), qb = g.ToVoxelCoordinates(b);
    double longest = -1.0;
    for (const Eigen::Vector3i& v : occupied) longest = std::max(longest, OverlapLength(qa, qb, v));
    if (longest > -1e-9 && longest < 1e-6) continue;  // grazes an edge: either answer is right
    ++decided;
    const bool truth = longest > 0.0;
    blocked += truth;
    EXPECT_EQ(SegmentBlocked(g, a, b), truth) << trial;
  }
  EXPECT_GT(decided, 2900);
  EXPECT_GT(blocked, 300);  // both answers were exercised
  EXPECT_LT(blocked, decided - 300);
}

// The two-level walk (bricks, then voxels in the bricks that hold a blocked one) answers as
// the plain voxel walk does, on a grid with clutter in some bricks and none in others.
TEST(SegmentBlocked, BrickWalkAnswersAsTheVoxelWalk) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> clutter(2.f, 6.f);
  PointCloud points(300);
  for (auto& p : points) p = {clutter(rng), clutter(rng), 0.2f * clutter(rng)};
  OccupancyOptions o;
  o.voxel_size_m = 0.1;
  o.clearance_m = 0.12;
  const OccupancyGrid g = OccupancyGrid::Build(points, Eigen::Vector3d::Zero(),
                                               Eigen::Vector3d(9.0, 9.0, 2.0), o);
  std::uniform_real_distribution<double> u(-1.0, 10.0), uz(-0.5, 2.5);
  int blocked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Eigen::Vector3d a(u(rng), u(rng), uz(rng)), b(u(rng), u(rng), uz(rng));
    const bool plain = WalkVoxels(g, a, b, [&g](const Eigen::Vector3i& v) {
      return g.TestBit(g.LinearIndex(v));
    });
    ASSERT_EQ(SegmentBlocked(g, a, b), plain) << trial;
    blocked += plain;
  }
  EXPECT_GT(blocked, 2000);
  EXPECT_LT(blocked, 18000);
}

// A line the grid calls clear passes every map point at the clearance or more; a blocked one
// passes some map point within BlockedReach(). Checked by the exact point-to-segment distance.
TEST(OccupancyGrid, InflationStaysWithinTheStatedClearanceBand) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> up(0.5f, 2.5f);
  PointCloud points(25);
  for (auto& p : points) p = {up(rng), up(rng), up(rng)};
  OccupancyOptions o;
  o.voxel_size_m = 0.1;
  o.clearance_m = 0.25;
  const OccupancyGrid g =
      OccupancyGrid::Build(points, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(3.0), o);
  EXPECT_GT(g.summary().blocked_voxels, 50 * g.summary().occupied_voxels);
  std::uniform_real_distribution<double> u(0.0, 3.0);
  const double low = o.clearance_m, high = o.BlockedReach();
  int blocked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    double nearest = 1e9;
    for (const Eigen::Vector3f& p : points) {
      const Eigen::Vector3d q = p.cast<double>();
      const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      nearest = std::min(nearest, (a + t * (b - a) - q).norm());
    }
    if (SegmentBlocked(g, a, b)) {
      ++blocked;
      EXPECT_LE(nearest, high + 1e-9) << trial;
    } else {
      EXPECT_GE(nearest, low - 1e-9) << trial;
    }
  }
  EXPECT_GT(blocked, 200);
}

TEST(OccupancyGrid, RefusesAGridLargerThanItsLimitAndNamesTheSize) {
  OccupancyOptions o;
  o.voxel_size_m = 0.05;
  o.max_voxels_million = 1;
  try {
    OccupancyGrid::Build({}, Eigen::Vector3d::Zero(), Eigen::Vector3d(100.0, 100.0, 10.0), o);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("max_voxels_million = 1"), std::string::npos) << e.what();
  }
}

TEST(OccupancyOptions, ValidationNamesTheField) {
  std::string why;
  OccupancyOptions o;
  EXPECT_TRUE(o.IsValid(&why)) << why;
  o.voxel_size_m = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("voxel_size_m = 0"), std::string::npos) << why;
  o = OccupancyOptions();
  o.clearance_m = std::nan("");
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("clearance_m"), std::string::npos) << why;
  o = OccupancyOptions();
  o.max_voxels_million = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("max_voxels_million = 0"), std::string::npos) << why;
}

}  // namespace
}  // namespace hylo::inspection
