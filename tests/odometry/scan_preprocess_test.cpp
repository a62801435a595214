// The pipeline's scan clean-up before registration: the ring stride (FAST-LIO2's
// point_filter_num) keeps every n-th return of each ring, whatever the rings' interleaving.
#include <gtest/gtest.h>

#include <vector>

#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/odometry/scan_preprocessor.h"

namespace hylo::odometry {
namespace {

// A wall 5 m ahead seen by `returns_per_ring.size()` rings, fired in turn as a spinning
// lidar does (ring 0, 1, ..., then the next column); ring r has returns_per_ring[r] returns.
LidarScan WallScan(const std::vector<int>& returns_per_ring) {
  LidarScan scan;
  scan.t_ns = 1'000'000'000;
  scan.end_t_ns = scan.t_ns + 100'000'000;
  int columns = 0;
  for (int n : returns_per_ring) columns = std::max(columns, n);
  for (int column = 0; column < columns; ++column) {
    for (std::size_t ring = 0; ring < returns_per_ring.size(); ++ring) {
      if (column >= returns_per_ring[ring]) continue;
      ScanPoint p;
      p.position_lidar = Eigen::Vector3f(5.f, -4.f + 0.02f * column, 0.25f * ring);
      p.offset_ns = column * 100'000;
      p.ring = static_cast<uint16_t>(ring);
      scan.points.push_back(p);
    }
  }
  return scan;
}

std::size_t PointsKeptForRegistration(const LidarScan& scan, int stride) {
  OdometryPipelineOptions options;
  options.imu.enabled = false;            // the first scan is registered at once
  options.preprocess.scan_voxel_m = 0.0;  // no voxel: the stride alone decides
  options.preprocess.point_stride = stride;
  OdometryPipeline pipeline(options);
  pipeline.AddScan(scan);
  std::vector<ScanResult> results;
  pipeline.Process(&results, /*flush=*/true);
  EXPECT_EQ(results.size(), 1u) << pipeline.message();
  if (results.empty()) return 0;
  EXPECT_EQ(results[0].raw_points, scan.points.size());
  return results[0].downsampled_points;
}

TEST(ScanPreprocess, StrideKeepsEveryNthReturnOfEachRing) {
  // Rings of unequal length: each keeps ceil(n / 4) of its own returns, which a stride over
  // the interleaved stream (keeping rings 0 and 4 of every column) would not.
  const LidarScan scan = WallScan({400, 399, 397, 50, 1});
  EXPECT_EQ(PointsKeptForRegistration(scan, 1), scan.points.size());
  EXPECT_EQ(PointsKeptForRegistration(scan, 4), 100u + 100u + 100u + 13u + 1u);
}

TEST(ScanPreprocess, StrideBelowOneIsRejectedWithItsName) {
  PreprocessOptions options;
  options.point_stride = 0;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("point_stride"), std::string::npos) << why;
  OdometryPipelineOptions pipeline;
  pipeline.preprocess.point_stride = -2;
  EXPECT_FALSE(pipeline.IsValid(&why));
  EXPECT_NE(why.find("preprocess.point_stride"), std::string::npos) << why;
}

}  // namespace
}  // namespace hylo::odometry
