// PointCloud2 decoding of odd and bad clouds: each failure names its reason, bad points are
// counted, and time bases follow the documented rules.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "hylo/logs/pointcloud2.h"

namespace hylo::logs {
namespace {

using hylo::LidarScan;
using hylo::ScanPoint;

constexpr int64_t kStampNs = 1600000000000000000;

/// |a - b| in ns, exact (EXPECT_NEAR would compare int64 epoch stamps as doubles).
int64_t AbsDiffNs(int64_t a, int64_t b) { return a > b ? a - b : b - a; }


LidarScan LineScan(int n) {
  LidarScan scan;
  scan.t_ns = kStampNs;
  for (int i = 0; i < n; ++i) {
    ScanPoint p;
    p.position_lidar = {1.f + i, 2.f, 3.f};
    p.offset_ns = 1000 * i;
    scan.points.push_back(p);
  }
  scan.end_t_ns = kStampNs + 1000 * (n - 1);
  return scan;
}

std::string DecodeError(const PointCloud2Message& cloud, PointTimeConvention convention) {
  try {
    DecodePointCloud2(cloud, convention, nullptr);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(PointCloud2BadInput, CloudWithoutXyzIsAnErrorListingTheFields) {
  PointCloud2Message cloud = EncodePointCloud2(LineScan(3), PointTimeConvention::kVelodyne);
  cloud.fields.erase(cloud.fields.begin() + 2);  // drop z
  const std::string why = DecodeError(cloud, PointTimeConvention::kAuto);
  EXPECT_NE(why.find("x/y/z"), std::string::npos) << why;
  EXPECT_NE(why.find("time:float32"), std::string::npos) << why;
}

TEST(PointCloud2BadInput, NonFinitePointsAndTimesAreDroppedAndCounted) {
  LidarScan scan = LineScan(10);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  scan.points[2].position_lidar.x() = nan;
  scan.points[5].position_lidar.z() = -inf;
  PointCloud2Message cloud = EncodePointCloud2(scan, PointTimeConvention::kVelodyne);
  EXPECT_FALSE(cloud.is_dense);
  std::memcpy(cloud.data.data() + 7 * cloud.point_step + 18, &nan, 4);  // time of point 7
  std::size_t dropped = 5;  // the count is added to, not reset
  const LidarScan out = DecodePointCloud2(cloud, PointTimeConvention::kAuto, &dropped);
  EXPECT_EQ(dropped, 5u + 3u);
  ASSERT_EQ(out.points.size(), 7u);
  for (const auto& p : out.points) EXPECT_TRUE(p.position_lidar.allFinite());
  EXPECT_EQ(out.end_t_ns, kStampNs + 9000);
}

TEST(PointCloud2BadInput, EmptyCloudGivesAnEmptyScanAtTheHeaderStamp) {
  for (auto layout : {PointTimeConvention::kVelodyne, PointTimeConvention::kHesai,
                      PointTimeConvention::kLivox}) {
    LidarScan empty;
    empty.t_ns = empty.end_t_ns = kStampNs;
    const LidarScan out = DecodePointCloud2(EncodePointCloud2(empty, layout), layout, nullptr);
    EXPECT_TRUE(out.points.empty());
    EXPECT_EQ(out.t_ns, kStampNs);
    EXPECT_EQ(out.end_t_ns, kStampNs);
  }
}

TEST(PointCloud2BadInput, MalformedLayoutsAreErrors) {
  const PointCloud2Message good = EncodePointCloud2(LineScan(4), PointTimeConvention::kVelodyne);
  PointCloud2Message past_step = good;
  past_step.fields.back().offset = 20;  // time (4 bytes) would end at 24 > point_step 22
  EXPECT_NE(DecodeError(past_step, PointTimeConvention::kAuto).find("past point_step"),
            std::string::npos);
  PointCloud2Message short_data = good;
  short_data.data.resize(good.data.size() - 1);
  EXPECT_NE(DecodeError(short_data, PointTimeConvention::kAuto).find("bytes"),
            std::string::npos);
  PointCloud2Message bad_type = good;
  bad_type.fields[3].datatype = 9;
  EXPECT_NE(DecodeError(bad_type, PointTimeConvention::kAuto).find("unknown datatype"),
            std::string::npos);
  PointCloud2Message short_rows = good;
  short_rows.row_step = good.point_step;
  EXPECT_NE(DecodeError(short_rows, PointTimeConvention::kAuto).find("row_step"),
            std::string::npos);
}

TEST(PointCloud2BadInput, ExplicitConventionWithoutItsTimeFieldIsAnError) {
  const PointCloud2Message cloud = EncodePointCloud2(LineScan(4), PointTimeConvention::kVelodyne);
  const std::string why = DecodeError(cloud, PointTimeConvention::kOuster);
  EXPECT_NE(why.find("'t'"), std::string::npos) << why;
}

TEST(PointCloud2BadInput, TimesSpanningMoreThanInt32NanosecondsAreAnError) {
  // Offsets of seconds mean a wrong convention or unit: refused rather than wrapped.
  const PointCloud2Message cloud = EncodePointCloud2(LineScan(4), PointTimeConvention::kVelodyne);
  PointCloud2Message wide = cloud;
  const float late = 5.0f;  // 5 s after the stamp: beyond an int32 of ns
  std::memcpy(wide.data.data() + 3 * wide.point_step + 18, &late, 4);
  EXPECT_NE(DecodeError(wide, PointTimeConvention::kAuto).find("span"), std::string::npos);
}

TEST(PointCloud2Decode, AbsoluteTimesStartAtTheEarliestPointWhereverItIs) {
  LidarScan scan = LineScan(5);
  PointCloud2Message cloud = EncodePointCloud2(scan, PointTimeConvention::kLivox);
  const double earliest = static_cast<double>(kStampNs - 500);
  std::memcpy(cloud.data.data() + 3 * cloud.point_step + 18, &earliest, 8);
  const LidarScan out = DecodePointCloud2(cloud, PointTimeConvention::kLivox, nullptr);
  // float64 ns near 1.6e18 come in 256 ns steps.
  EXPECT_LE(AbsDiffNs(out.t_ns, kStampNs - 500), 256);
  EXPECT_EQ(out.points[3].offset_ns, 0);
  EXPECT_LE(AbsDiffNs(out.points[0].offset_ns, 500), 256);
}

TEST(PointCloud2Decode, NegativeRelativeOffsetsMoveTheStartToTheEarliestPoint) {
  PointCloud2Message cloud = EncodePointCloud2(LineScan(3), PointTimeConvention::kVelodyne);
  const float before = -0.05f;  // a driver stamping the scan after its first returns
  std::memcpy(cloud.data.data() + 18, &before, 4);
  const LidarScan out = DecodePointCloud2(cloud, PointTimeConvention::kVelodyne, nullptr);
  EXPECT_LE(AbsDiffNs(out.t_ns, kStampNs - 50000000), 5);
  for (const auto& p : out.points) EXPECT_GE(p.offset_ns, 0);
  EXPECT_EQ(out.end_t_ns, kStampNs + 2000);
}

TEST(PointCloud2Decode, OrganizedCloudWithRowPadding) {
  const PointCloud2Message flat = EncodePointCloud2(LineScan(6), PointTimeConvention::kOuster);
  PointCloud2Message organized = flat;
  organized.height = 2;
  organized.width = 3;
  organized.row_step = 3 * flat.point_step + 8;  // 8 padding bytes after each row
  organized.data.assign(2 * organized.row_step, 0xAB);
  for (int row = 0; row < 2; ++row) {
    std::memcpy(organized.data.data() + row * organized.row_step,
                flat.data.data() + row * 3 * flat.point_step, 3 * flat.point_step);
  }
  const LidarScan a = DecodePointCloud2(flat, PointTimeConvention::kAuto, nullptr);
  const LidarScan b = DecodePointCloud2(organized, PointTimeConvention::kAuto, nullptr);
  ASSERT_EQ(b.points.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(a.points[i].position_lidar, b.points[i].position_lidar);
    EXPECT_EQ(a.points[i].offset_ns, b.points[i].offset_ns);
  }
}

}  // namespace
}  // namespace hylo::logs
