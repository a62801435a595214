// PointCloud2 <-> LidarScan: every driver layout round-trips, is detected from its fields,
// and malformed clouds fail with a reason. No ROS needed: the message is the plain mirror.

#include "hylo/logs/pointcloud2.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

namespace hylo::logs {
namespace {

using hylo::LidarScan;
using hylo::ScanPoint;

constexpr int64_t kStartNs = 1700000000123456789;  // a realistic epoch stamp

/// |a - b| in ns, exact (EXPECT_NEAR would compare int64 epoch stamps as doubles).
int64_t AbsDiffNs(int64_t a, int64_t b) { return a > b ? a - b : b - a; }


/// A sweep of `n` returns over 0.1 s; the first return at the scan start.
LidarScan RandomScan(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord(-80.f, 80.f);
  std::uniform_int_distribution<int> offset(0, 99999999);
  std::uniform_int_distribution<int> ring(0, 127);
  std::uniform_int_distribution<int> intensity(0, 255);
  LidarScan scan;
  scan.t_ns = kStartNs;
  scan.frame_id = "lidar";
  for (int i = 0; i < n; ++i) {
    ScanPoint p;
    p.position_lidar = {coord(rng), coord(rng), coord(rng)};
    p.intensity = static_cast<float>(intensity(rng));
    p.offset_ns = i == 0 ? 0 : offset(rng);
    p.ring = static_cast<uint16_t>(ring(rng));
    scan.points.push_back(p);
  }
  int32_t max_offset = 0;
  for (const auto& p : scan.points) max_offset = std::max(max_offset, p.offset_ns);
  scan.end_t_ns = scan.t_ns + max_offset;
  return scan;
}

struct LayoutCase {
  PointTimeConvention layout;
  PointTimeConvention detected;  ///< what kAuto must find in the written fields
  uint32_t point_step;           ///< as the driver writes it
  int64_t time_tolerance_ns;     ///< float32 s offsets: ~4 ns; f64 epoch s or ns: ~128 ns
};

class LayoutTest : public ::testing::TestWithParam<LayoutCase> {};

TEST_P(LayoutTest, RoundTripKeepsPointsAndTimes) {
  const LayoutCase c = GetParam();
  const LidarScan scan = RandomScan(2000, 7);
  const PointCloud2Message cloud = EncodePointCloud2(scan, c.layout);
  EXPECT_EQ(cloud.point_step, c.point_step);
  EXPECT_EQ(cloud.data.size(), scan.points.size() * c.point_step);
  std::size_t dropped = 0;
  const LidarScan out = DecodePointCloud2(cloud, PointTimeConvention::kAuto, &dropped);
  EXPECT_EQ(dropped, 0u);
  ASSERT_EQ(out.points.size(), scan.points.size());
  EXPECT_EQ(out.frame_id, "lidar");
  const bool has_time = c.layout != PointTimeConvention::kNone;
  EXPECT_LE(AbsDiffNs(out.t_ns, scan.t_ns), has_time ? c.time_tolerance_ns : 0);
  if (has_time) {
    EXPECT_LE(AbsDiffNs(out.end_t_ns, scan.end_t_ns), c.time_tolerance_ns);
  }
  int64_t worst_ns = 0;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const ScanPoint& a = scan.points[i];
    const ScanPoint& b = out.points[i];
    ASSERT_EQ(a.position_lidar, b.position_lidar) << i;
    EXPECT_EQ(a.intensity, b.intensity) << i;
    EXPECT_EQ(b.ring, c.layout == PointTimeConvention::kNone ? 0 : a.ring) << i;
    const int64_t want = has_time ? scan.t_ns + a.offset_ns : out.t_ns;
    worst_ns = std::max<int64_t>(worst_ns, std::llabs(out.t_ns + b.offset_ns - want));
  }
  std::printf("%s: worst per-point time error %lld ns\n", ToString(c.layout).c_str(),
              static_cast<long long>(worst_ns));
  EXPECT_LE(worst_ns, c.time_tolerance_ns);
  EXPECT_LE(worst_ns, 1000);  // the project's requirement: 1 us or better
}

TEST_P(LayoutTest, AutoDetectionFindsTheWrittenLayout) {
  const LayoutCase c = GetParam();
  const PointCloud2Message cloud = EncodePointCloud2(RandomScan(10, 3), c.layout);
  EXPECT_EQ(DetectPointTimeConvention(cloud.fields), c.detected);
}

TEST_P(LayoutTest, ExplicitConventionDecodesLikeAuto) {
  const LayoutCase c = GetParam();
  const PointCloud2Message cloud = EncodePointCloud2(RandomScan(50, 5), c.layout);
  const LidarScan a = DecodePointCloud2(cloud, c.layout, nullptr);
  const LidarScan b = DecodePointCloud2(cloud, PointTimeConvention::kAuto, nullptr);
  ASSERT_EQ(a.points.size(), b.points.size());
  EXPECT_EQ(a.t_ns, b.t_ns);
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].offset_ns, b.points[i].offset_ns);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Drivers, LayoutTest,
    ::testing::Values(
        LayoutCase{PointTimeConvention::kVelodyne, PointTimeConvention::kVelodyne, 22, 10},
        LayoutCase{PointTimeConvention::kOuster, PointTimeConvention::kOuster, 48, 0},
        LayoutCase{PointTimeConvention::kHesai, PointTimeConvention::kHesai, 26, 250},
        LayoutCase{PointTimeConvention::kRobosense, PointTimeConvention::kHesai, 26, 250},
        LayoutCase{PointTimeConvention::kLivox, PointTimeConvention::kLivox, 26, 250},
        LayoutCase{PointTimeConvention::kNone, PointTimeConvention::kNone, 16, 0}),
    [](const ::testing::TestParamInfo<LayoutCase>& info) {
      return ToString(info.param.layout);
    });

TEST(PointCloud2Layout, RobosenseStampsTheLastPointOthersTheFirst) {
  const LidarScan scan = RandomScan(100, 11);
  EXPECT_EQ(EncodePointCloud2(scan, PointTimeConvention::kRobosense).stamp_ns, scan.end_t_ns);
  EXPECT_EQ(EncodePointCloud2(scan, PointTimeConvention::kVelodyne).stamp_ns, scan.t_ns);
  // Absolute conventions ignore the header for point times: decoding still starts at t_ns.
  const LidarScan out =
      DecodePointCloud2(EncodePointCloud2(scan, PointTimeConvention::kRobosense),
                        PointTimeConvention::kRobosense, nullptr);
  EXPECT_LE(AbsDiffNs(out.t_ns, scan.t_ns), 250);
}

PointCloud2Message SinglePointCloud(std::vector<PointFieldInfo> fields, uint32_t point_step) {
  PointCloud2Message cloud;
  cloud.stamp_ns = kStartNs;
  cloud.width = 1;
  cloud.fields = std::move(fields);
  cloud.point_step = point_step;
  cloud.row_step = point_step;
  cloud.data.assign(point_step, 0);
  return cloud;
}

template <typename T>
void Put(PointCloud2Message* cloud, uint32_t offset, T value) {
  std::memcpy(cloud->data.data() + offset, &value, sizeof(T));
}

TEST(PointCloud2Decode, ReadsEveryDatatype) {
  PointCloud2Message cloud = SinglePointCloud({{"x", kInt8, 0, 1},
                                               {"y", kInt16, 1, 1},
                                               {"z", kFloat64, 3, 1},
                                               {"intensity", kInt32, 11, 1},
                                               {"ring", kUint8, 15, 1},
                                               {"t", kUint32, 16, 1},
                                               {"extra", kUint16, 20, 1}},
                                              22);
  Put<int8_t>(&cloud, 0, -7);
  Put<int16_t>(&cloud, 1, -300);
  Put<double>(&cloud, 3, 2.5);
  Put<int32_t>(&cloud, 11, 70000);
  Put<uint8_t>(&cloud, 15, 200);
  Put<uint32_t>(&cloud, 16, 123456789u);
  const LidarScan scan = DecodePointCloud2(cloud, PointTimeConvention::kAuto, nullptr);
  ASSERT_EQ(scan.points.size(), 1u);
  EXPECT_EQ(scan.points[0].position_lidar, Eigen::Vector3f(-7.f, -300.f, 2.5f));
  EXPECT_EQ(scan.points[0].intensity, 70000.f);
  EXPECT_EQ(scan.points[0].ring, 200);
  EXPECT_EQ(scan.t_ns, kStartNs);  // relative convention: t_ns = header.stamp
  EXPECT_EQ(scan.points[0].offset_ns, 123456789);
  EXPECT_EQ(scan.end_t_ns, kStartNs + 123456789);
}

TEST(PointCloud2Decode, OlderOusterLayoutWithUint8RingAndUint16Time) {
  // ouster_example's Point had `ring` as uint8; also accept any integer type for `t`.
  PointCloud2Message cloud = SinglePointCloud(
      {{"x", kFloat32, 0, 1}, {"y", kFloat32, 4, 1}, {"z", kFloat32, 8, 1},
       {"t", kUint16, 16, 1}, {"ring", kUint8, 26, 1}}, 48);
  Put<float>(&cloud, 0, 1.f);
  Put<uint16_t>(&cloud, 16, 5000);
  Put<uint8_t>(&cloud, 26, 63);
  const LidarScan scan = DecodePointCloud2(cloud, PointTimeConvention::kAuto, nullptr);
  ASSERT_EQ(scan.points.size(), 1u);
  EXPECT_EQ(scan.points[0].ring, 63);
  EXPECT_EQ(scan.points[0].offset_ns, 5000);
}

/// Reverses the bytes of every field of every point: the big-endian form of the cloud.
PointCloud2Message ToBigEndian(PointCloud2Message cloud) {
  for (uint32_t i = 0; i < cloud.width; ++i) {
    for (const auto& f : cloud.fields) {
      uint8_t* p = cloud.data.data() + i * cloud.point_step + f.offset;
      std::reverse(p, p + PointFieldSize(f.datatype));
    }
  }
  cloud.is_bigendian = true;
  return cloud;
}

TEST(PointCloud2Decode, BigEndianCloudsAreSwapped) {
  const LidarScan scan = RandomScan(100, 13);
  for (auto layout : {PointTimeConvention::kVelodyne, PointTimeConvention::kOuster,
                      PointTimeConvention::kLivox}) {
    const PointCloud2Message little = EncodePointCloud2(scan, layout);
    const LidarScan a = DecodePointCloud2(little, layout, nullptr);
    const LidarScan b = DecodePointCloud2(ToBigEndian(little), layout, nullptr);
    ASSERT_EQ(a.points.size(), b.points.size());
    EXPECT_EQ(a.t_ns, b.t_ns);
    for (std::size_t i = 0; i < a.points.size(); ++i) {
      EXPECT_EQ(a.points[i].position_lidar, b.points[i].position_lidar);
      EXPECT_EQ(a.points[i].offset_ns, b.points[i].offset_ns);
      EXPECT_EQ(a.points[i].ring, b.points[i].ring);
    }
  }
}

}  // namespace
}  // namespace hylo::logs
