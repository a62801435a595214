// Bags with bad data (NaN points, NaN IMU, empty scans, clouds without x/y/z), streaming
// (a bag is read lazily, memory does not grow with it) and DescribeBag.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/logs/bag_reader.h"
#include "hylo/logs/bag_writer.h"
#include "test_data.h"

namespace hylo::logs {
namespace {

using hylo::ImuSample;
using hylo::LidarScan;

constexpr int64_t kStartNs = 1650000000000000000;

LidarScan GridScan(int64_t t_ns, int n) {
  LidarScan scan;
  scan.t_ns = t_ns;
  for (int i = 0; i < n; ++i) {
    ScanPoint p;
    p.position_lidar = {0.01f * i, 5.f, -1.f};
    p.offset_ns = i * 1000;
    p.ring = static_cast<uint16_t>(i % 16);
    scan.points.push_back(p);
  }
  scan.end_t_ns = t_ns + (n > 0 ? (n - 1) * 1000 : 0);
  return scan;
}

LogReadOptions Options() {
  LogReadOptions options;
  options.lidar_topic = "/points";
  options.imu_topic = "/imu";
  return options;
}

TEST(BagData, NonFinitePointsImuAndEmptyScansAreCounted) {
  const std::string path = testing::ScratchDir("bag_bad_data") + "/a.bag";
  const float nan = std::numeric_limits<float>::quiet_NaN();
  {
    BagWriter writer(path);
    ImuSample imu;
    imu.t_ns = kStartNs;
    writer.WriteImu("/imu", imu, "imu");
    imu.t_ns += 1000000;
    imu.gyro_imu.y() = std::numeric_limits<double>::infinity();
    writer.WriteImu("/imu", imu, "imu");
    imu.t_ns += 1000000;
    imu.gyro_imu.y() = 0.0;
    imu.accel_imu.x() = std::numeric_limits<double>::quiet_NaN();
    writer.WriteImu("/imu", imu, "imu");
    LidarScan scan = GridScan(kStartNs + 10000000, 100);
    scan.points[10].position_lidar.y() = nan;
    scan.points[20].position_lidar.z() = std::numeric_limits<float>::infinity();
    scan.points[30].position_lidar.x() = nan;
    writer.WriteScan("/points", scan, PointTimeConvention::kVelodyne, "lidar");
    writer.WriteScan("/points", GridScan(kStartNs + 20000000, 0), PointTimeConvention::kVelodyne,
                     "lidar");
    writer.Close();
  }
  auto reader = OpenBag(path, Options());
  LogMessage m;
  std::vector<std::size_t> scan_sizes;
  std::size_t imu = 0;
  while (reader->Next(&m)) {
    if (m.kind == LogMessage::Kind::kScan) {
      scan_sizes.push_back(m.scan.points.size());
      if (m.scan.points.empty()) {
        EXPECT_EQ(m.scan.t_ns, kStartNs + 20000000);
      }
    } else {
      ++imu;
      EXPECT_TRUE(m.imu.accel_imu.allFinite() && m.imu.gyro_imu.allFinite());
    }
  }
  EXPECT_EQ(scan_sizes, (std::vector<std::size_t>{97, 0}));  // the empty scan is delivered
  EXPECT_EQ(imu, 1u);
  const LogReadCounters& c = reader->counters();
  EXPECT_EQ(c.dropped_non_finite_points, 3u);
  EXPECT_EQ(c.dropped_non_finite_imu, 2u);
  EXPECT_EQ(c.empty_scans, 1u);
  EXPECT_EQ(c.scan_messages, 2u);
  EXPECT_EQ(c.imu_messages, 1u);
}

TEST(BagData, CloudWithoutXyzIsAnErrorAtOpen) {
  const std::string path = testing::ScratchDir("bag_no_xyz") + "/a.bag";
  {
    BagWriter writer(path);
    PointCloud2Message cloud = EncodePointCloud2(GridScan(kStartNs, 5), PointTimeConvention::kNone);
    cloud.fields[0].name = "range";  // x renamed: a range image, not a point cloud
    writer.WriteCloud("/points", cloud, kStartNs);
    ImuSample imu;
    imu.t_ns = kStartNs;
    writer.WriteImu("/imu", imu, "imu");
  }  // the destructor closes the bag
  try {
    OpenBag(path, Options());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string why = e.what();
    EXPECT_NE(why.find(path), std::string::npos) << why;
    EXPECT_NE(why.find("x/y/z"), std::string::npos) << why;
  }
}

/// Bytes read by this process so far (the kernel's rchar: every read() call, cache or not).
uint64_t BytesRead() {
  std::ifstream io("/proc/self/io");
  std::string key;
  uint64_t value = 0;
  while (io >> key >> value) {
    if (key == "rchar:") return value;
  }
  return 0;
}

/// Resident memory of this process, bytes.
uint64_t ResidentBytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  }
  return 0;
}

TEST(BagData, ReadingStreamsTheBag) {
  if (BytesRead() == 0 || ResidentBytes() == 0) GTEST_SKIP() << "no /proc/self/{io,status}";
  const std::string path = testing::ScratchDir("bag_streaming") + "/big.bag";
  constexpr int kScans = 150;
  constexpr int kPoints = 10000;  // 22 bytes each in the Velodyne layout: ~33 MB of scans
  {
    BagWriter writer(path);
    for (int i = 0; i < kScans; ++i) {
      writer.WriteScan("/points", GridScan(kStartNs + i * 100000000LL, kPoints),
                       PointTimeConvention::kVelodyne, "lidar");
    }
    writer.Close();
  }
  const uint64_t bag_bytes = std::filesystem::file_size(path);
  LogReadOptions options = Options();
  options.imu_topic.clear();
  const uint64_t read_before = BytesRead();
  const uint64_t rss_before = ResidentBytes();
  auto reader = OpenBag(path, options);
  LogMessage m;
  ASSERT_TRUE(reader->Next(&m));
  const uint64_t read_at_first = BytesRead() - read_before;
  uint64_t rss_peak = ResidentBytes();
  int scans = 1;
  while (reader->Next(&m)) {
    ++scans;
    rss_peak = std::max(rss_peak, ResidentBytes());
  }
  const uint64_t read_total = BytesRead() - read_before;
  std::printf("bag %.1f MB: read %.2f MB to deliver the first scan, %.1f MB in all; "
              "resident memory grew by at most %.1f MB\n",
              bag_bytes / 1e6, read_at_first / 1e6, read_total / 1e6,
              (rss_peak - std::min(rss_peak, rss_before)) / 1e6);
  EXPECT_EQ(scans, kScans);
  EXPECT_LT(read_at_first, bag_bytes / 10);    // lazily: not the whole bag up front
  EXPECT_GT(read_total, bag_bytes * 9 / 10);   // and everything by the end
  EXPECT_LT(rss_peak - std::min(rss_peak, rss_before), bag_bytes / 4);
}

TEST(BagData, DescribeBagReportsTopicsRatesStampsAndFields) {
  const std::string path = testing::ScratchDir("bag_describe") + "/a.bag";
  {
    BagWriter writer(path);
    for (int i = 0; i < 400; ++i) {  // 2 s of 200 Hz IMU, 20 scans at 10 Hz
      ImuSample imu;
      imu.t_ns = kStartNs + i * 5000000LL;
      writer.WriteImu("/imu", imu, "imu");
      if (i % 20 == 0) {
        writer.WriteScan("/os_cloud_node/points", GridScan(imu.t_ns, 50),
                         PointTimeConvention::kOuster, "os_lidar");
      }
    }
    writer.Close();
  }
  const BagDescription d = DescribeBag(path);
  ASSERT_EQ(d.topics.size(), 2u);
  EXPECT_EQ(d.message_count, 420u);
  EXPECT_EQ(d.start_ns, kStartNs);
  EXPECT_EQ(d.end_ns, kStartNs + 399 * 5000000LL);  // the last IMU is after the last scan end
  EXPECT_NEAR(d.duration_s, 1.995, 1e-9);
  const BagTopicDescription& imu = d.topics[0];  // sorted: "/imu" < "/os_cloud_node/points"
  EXPECT_EQ(imu.name, "/imu");
  EXPECT_EQ(imu.type, "sensor_msgs/Imu");
  EXPECT_EQ(imu.message_count, 400u);
  EXPECT_NEAR(imu.mean_rate_hz, 200.0, 1e-6);
  EXPECT_TRUE(imu.stamps_from_header);
  EXPECT_EQ(imu.last_stamp_ns, kStartNs + 399 * 5000000LL);
  const BagTopicDescription& cloud = d.topics[1];
  EXPECT_EQ(cloud.type, "sensor_msgs/PointCloud2");
  EXPECT_EQ(cloud.message_count, 20u);
  EXPECT_NEAR(cloud.mean_rate_hz, 10.0, 1e-6);
  EXPECT_EQ(cloud.first_stamp_ns, kStartNs);
  EXPECT_EQ(cloud.detected_convention, PointTimeConvention::kOuster);
  ASSERT_EQ(cloud.point_fields.size(), 9u);
  EXPECT_EQ(cloud.point_fields[4].name, "t");
  EXPECT_EQ(cloud.point_fields[4].datatype, kUint32);
  EXPECT_EQ(cloud.point_fields[4].offset, 20u);
}

TEST(BagData, DescribeMissingBagNamesIt) {
  const std::string path = testing::ScratchDir("bag_describe_missing") + "/none.bag";
  try {
    DescribeBag(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
  }
}

}  // namespace
}  // namespace hylo::logs
