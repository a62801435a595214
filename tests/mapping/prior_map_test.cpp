// Prior map loading: UTM-sized coordinates computed near zero, downsampling to the map
// resolution, and errors for empty / all-NaN maps.
#include "hylo/mapping/prior_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hylo/registration/voxel_filter.h"

namespace hylo::mapping {
namespace {

// A 20 m x 20 m patch of points every 2 cm around `centre_world`.
std::vector<Eigen::Vector3d> Patch(const Eigen::Vector3d& centre_world) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 1000; ++i) {
    for (int j = 0; j < 1000; j += 10) {
      points.push_back(centre_world + Eigen::Vector3d(-10 + 0.02 * i, -10 + 0.02 * j,
                                                      0.001 * (i % 7)));
    }
  }
  return points;
}

TEST(PriorMap, UtmCoordinatesAreKeptToTheMillimetreNearZero) {
  const Eigen::Vector3d utm(512345.678, 4412345.321, 231.5);
  const std::vector<Eigen::Vector3d> world = Patch(utm);
  PriorMapOptions options;
  options.resolution_m = 0.0;  // keep every point: compare one for one
  const PriorMap map = BuildPriorMap(world, options, "utm.pcd");
  ASSERT_EQ(map.num_kept, world.size());
  // The origin is round, and local coordinates are small enough for float.
  EXPECT_EQ(map.origin_world.x(), std::round(map.origin_world.x() / 100.0) * 100.0);
  double max_error = 0.0, max_local = 0.0;
  for (std::size_t i = 0; i < world.size(); ++i) {
    max_local = std::max(max_local, static_cast<double>(map.points_local[i].norm()));
    max_error = std::max(max_error, (map.points_local[i].cast<double>() + map.origin_world -
                                     world[i]).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(max_local, 200.0);
  EXPECT_LT(max_error, 1e-4);  // float at 4.4e6 m would be off by 0.25 m
  // A world pose round-trips through the local frame.
  Eigen::Isometry3d T_world = Eigen::Isometry3d::Identity();
  T_world.translation() = utm + Eigen::Vector3d(1, 2, 3);
  const Eigen::Isometry3d T_local = PoseToLocal(T_world, map.origin_world);
  EXPECT_LT(T_local.translation().norm(), 200.0);
  EXPECT_TRUE(PoseToWorld(T_local, map.origin_world).isApprox(T_world));
}

TEST(PriorMap, DownsamplesToTheResolutionAndCountsNaN) {
  std::vector<Eigen::Vector3d> world = Patch(Eigen::Vector3d(500000.0, 4400000.0, 100.0));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  world.push_back(Eigen::Vector3d(nan, 0, 0));
  world.push_back(Eigen::Vector3d(1, std::numeric_limits<double>::infinity(), 0));
  PriorMapOptions options;
  options.resolution_m = 0.5;
  const PriorMap map = BuildPriorMap(world, options);
  EXPECT_EQ(map.num_input, world.size());
  EXPECT_EQ(map.num_non_finite, 2u);
  EXPECT_EQ(map.num_kept, map.points_local.size());
  // 20 m x 20 m at 0.5 m: about 40 x 40 occupied voxels (41 where the patch straddles a face).
  EXPECT_GE(map.num_kept, 1600u);
  EXPECT_LE(map.num_kept, 41u * 41u);
  // At most one point per voxel, and every kept point is an input point.
  const PointCloud again = registration::UniformSample(map.points_local, 0.5f);
  EXPECT_EQ(again.size(), map.points_local.size());
  for (const Eigen::Vector3f& p : map.points_local) ASSERT_TRUE(p.allFinite());
}

TEST(PriorMap, EmptyAndAllNanMapsAreClearErrors) {
  PriorMapOptions options;
  try {
    BuildPriorMap({}, options, "site.pcd");
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("site.pcd: the map has no point"), std::string::npos);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  try {
    BuildPriorMap(std::vector<Eigen::Vector3d>(3, Eigen::Vector3d(nan, nan, nan)), options,
                  "nan.ply");
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nan.ply: all 3 map points are NaN"), std::string::npos)
        << e.what();
  }
  options.resolution_m = -1.0;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("resolution_m = -1"), std::string::npos);
  EXPECT_THROW(BuildPriorMap({Eigen::Vector3d::Zero()}, options), std::invalid_argument);
}

}  // namespace
}  // namespace hylo::mapping
