// ROS1 bags: write -> read round trip for every driver layout, receive order, DescribeBag,
// and every documented failure (missing file, not a bag, missing topic, wrong type, no x/y/z);
// truncated and unindexed bags are read up to their last complete message.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
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

constexpr int64_t kStartNs = 1700000000000000000;
constexpr int64_t kImuPeriodNs = 5000000;     // 200 Hz
constexpr int64_t kScanPeriodNs = 100000000;  // 10 Hz

LidarScan MakeScan(int64_t t_ns, int n, std::mt19937* rng) {
  std::uniform_real_distribution<float> coord(-50.f, 50.f);
  std::uniform_int_distribution<int> offset(1, kScanPeriodNs - 1);
  LidarScan scan;
  scan.t_ns = t_ns;
  scan.end_t_ns = t_ns;
  for (int i = 0; i < n; ++i) {
    ScanPoint p;
    p.position_lidar = {coord(*rng), coord(*rng), coord(*rng)};
    p.intensity = static_cast<float>(i % 256);
    p.ring = static_cast<uint16_t>(i % 32);
    p.offset_ns = i == 0 ? 0 : offset(*rng);
    scan.end_t_ns = std::max(scan.end_t_ns, t_ns + p.offset_ns);
    scan.points.push_back(p);
  }
  return scan;
}

ImuSample MakeImu(int64_t t_ns, std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, 0.3);
  ImuSample imu;
  imu.t_ns = t_ns;
  imu.accel_imu = {noise(*rng), noise(*rng), 9.81 + noise(*rng)};
  imu.gyro_imu = {noise(*rng), noise(*rng), noise(*rng)};
  return imu;
}

/// What a test bag holds, to compare the reader against.
struct Recording {
  std::vector<ImuSample> imu;
  std::vector<LidarScan> scans;
};

/// One second of 200 Hz IMU and 10 Hz scans, written in time order like a recorder would.
Recording WriteRecording(const std::string& path, PointTimeConvention layout, int points) {
  std::mt19937 rng(42);
  Recording rec;
  BagWriter writer(path);
  for (int64_t t = kStartNs; t <= kStartNs + 1000000000; t += kImuPeriodNs) {
    rec.imu.push_back(MakeImu(t, &rng));
    writer.WriteImu("/imu", rec.imu.back(), "imu");
    if ((t - kStartNs) % kScanPeriodNs == 0 && t < kStartNs + 1000000000) {
      rec.scans.push_back(MakeScan(t, points, &rng));
      writer.WriteScan("/points", rec.scans.back(), layout, "lidar");
    }
  }
  writer.Close();
  return rec;
}

LogReadOptions Options() {
  LogReadOptions options;
  options.lidar_topic = "/points";
  options.imu_topic = "/imu";
  return options;
}

std::string OpenError(const std::string& path, const LogReadOptions& options) {
  try {
    OpenBag(path, options);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

class BagRoundTrip : public ::testing::TestWithParam<PointTimeConvention> {};

TEST_P(BagRoundTrip, ReadsBackEveryMessageInReceiveOrder) {
  const PointTimeConvention layout = GetParam();
  const std::string path = testing::ScratchDir("bag_round_trip_" + ToString(layout)) + "/a.bag";
  const Recording rec = WriteRecording(path, layout, 500);
  auto reader = OpenBag(path, Options());
  const PointTimeConvention want = layout == PointTimeConvention::kRobosense
                                       ? PointTimeConvention::kHesai  // same bytes
                                       : layout;
  EXPECT_EQ(reader->time_convention(), want);
  std::size_t next_imu = 0, next_scan = 0;
  int64_t last_receive_ns = 0;
  LogMessage m;
  while (reader->Next(&m)) {
    if (m.kind == LogMessage::Kind::kImu) {
      ASSERT_LT(next_imu, rec.imu.size());
      const ImuSample& want_imu = rec.imu[next_imu++];
      EXPECT_EQ(m.imu.t_ns, want_imu.t_ns);
      EXPECT_EQ(m.imu.accel_imu, want_imu.accel_imu);
      EXPECT_EQ(m.imu.gyro_imu, want_imu.gyro_imu);
      EXPECT_GE(m.imu.t_ns, last_receive_ns);
      last_receive_ns = m.imu.t_ns;
      continue;
    }
    ASSERT_LT(next_scan, rec.scans.size());
    const LidarScan& want_scan = rec.scans[next_scan++];
    ASSERT_EQ(m.scan.points.size(), want_scan.points.size());
    EXPECT_EQ(m.scan.frame_id, "lidar");
    EXPECT_GE(m.scan.end_t_ns + 1000, last_receive_ns);  // received at its end time
    last_receive_ns = want_scan.end_t_ns;
    for (std::size_t i = 0; i < want_scan.points.size(); ++i) {
      const auto& a = want_scan.points[i];
      const auto& b = m.scan.points[i];
      ASSERT_EQ(a.position_lidar, b.position_lidar);
      ASSERT_EQ(a.intensity, b.intensity);
      ASSERT_EQ(a.ring, b.ring);
      ASSERT_LE(std::llabs((m.scan.t_ns + b.offset_ns) - (want_scan.t_ns + a.offset_ns)), 1000)
          << "point " << i << " of scan " << next_scan - 1;
    }
  }
  EXPECT_EQ(next_imu, rec.imu.size());
  EXPECT_EQ(next_scan, rec.scans.size());
  EXPECT_EQ(reader->counters().imu_messages, rec.imu.size());
  EXPECT_EQ(reader->counters().scan_messages, rec.scans.size());
  EXPECT_EQ(reader->counters().dropped_non_finite_points, 0u);
  EXPECT_FALSE(reader->Next(&m));  // stays at the end
}

INSTANTIATE_TEST_SUITE_P(Drivers, BagRoundTrip,
                         ::testing::Values(PointTimeConvention::kVelodyne,
                                           PointTimeConvention::kOuster,
                                           PointTimeConvention::kHesai,
                                           PointTimeConvention::kRobosense,
                                           PointTimeConvention::kLivox),
                         [](const auto& info) { return ToString(info.param); });

TEST(BagReader, ExplicitConventionIsKept) {
  const std::string path = testing::ScratchDir("bag_explicit") + "/a.bag";
  WriteRecording(path, PointTimeConvention::kRobosense, 10);
  LogReadOptions options = Options();
  options.time_convention = PointTimeConvention::kRobosense;
  EXPECT_EQ(OpenBag(path, options)->time_convention(), PointTimeConvention::kRobosense);
}

TEST(BagReader, AccelScaleConvertsDriversThatReportG) {
  const std::string path = testing::ScratchDir("bag_accel_scale") + "/a.bag";
  const Recording rec = WriteRecording(path, PointTimeConvention::kVelodyne, 10);
  LogReadOptions options = Options();
  options.imu_accel_scale = 9.81;
  auto reader = OpenBag(path, options);
  LogMessage m;
  std::size_t n = 0;
  while (reader->Next(&m)) {
    if (m.kind != LogMessage::Kind::kImu) continue;
    EXPECT_TRUE(m.imu.accel_imu.isApprox(9.81 * rec.imu[n].accel_imu, 1e-12));
    EXPECT_TRUE(m.imu.gyro_imu.isApprox(rec.imu[n].gyro_imu, 1e-12)) << "gyro is not scaled";
    ++n;
  }
  EXPECT_EQ(n, rec.imu.size());
}

TEST(BagReader, ImuTopicMayBeOmitted) {
  const std::string path = testing::ScratchDir("bag_no_imu") + "/a.bag";
  const Recording rec = WriteRecording(path, PointTimeConvention::kOuster, 10);
  LogReadOptions options = Options();
  options.imu_topic.clear();
  auto reader = OpenBag(path, options);
  LogMessage m;
  std::size_t scans = 0;
  while (reader->Next(&m)) scans += m.kind == LogMessage::Kind::kScan;
  EXPECT_EQ(scans, rec.scans.size());
  EXPECT_EQ(reader->counters().imu_messages, 0u);
}

TEST(BagReader, MissingFileNamesThePath) {
  const std::string path = testing::ScratchDir("bag_missing") + "/nothing.bag";
  const std::string why = OpenError(path, Options());
  EXPECT_NE(why.find(path), std::string::npos) << why;
  EXPECT_NE(why.find("no such file"), std::string::npos) << why;
}

// Cut and killed bags in detail: bag_recovery_test.
TEST(BagReader, TruncatedBagIsReadUpToTheCut) {
  const std::string path = testing::ScratchDir("bag_truncated") + "/cut.bag";
  const Recording rec = WriteRecording(path, PointTimeConvention::kVelodyne, 200);
  const auto size = std::filesystem::file_size(path);
  std::size_t last_scans = rec.scans.size();
  for (double keep : {0.999, 0.9, 0.3}) {
    std::filesystem::resize_file(path, static_cast<uintmax_t>(size * keep));
    auto reader = OpenBag(path, Options());
    LogMessage m;
    std::size_t scans = 0;
    while (reader->Next(&m)) scans += m.kind == LogMessage::Kind::kScan;
    ASSERT_NE(reader->recovery(), nullptr) << keep;
    EXPECT_EQ(reader->recovery()->file_bytes, static_cast<uint64_t>(size * keep));
    EXPECT_GT(scans, 0u) << keep;
    EXPECT_LE(scans, last_scans) << keep;  // less kept, never more read
    last_scans = scans;
    EXPECT_TRUE(DescribeBag(path).recovery.has_value());
  }
  EXPECT_LT(last_scans, rec.scans.size() / 2);  // 30 % of the bytes
}

TEST(BagReader, InterruptedRecordingIsReadWithoutItsIndex) {
  const std::string dir = testing::ScratchDir("bag_unindexed");
  std::mt19937 rng(1);
  BagWriter writer(dir + "/live.bag");
  for (int i = 0; i < 20; ++i) {  // ~1.5 MB: several chunks reach the disk, no index yet
    writer.WriteScan("/points", MakeScan(kStartNs + i * kScanPeriodNs, 3000, &rng),
                     PointTimeConvention::kVelodyne, "lidar");
  }
  std::filesystem::copy_file(dir + "/live.bag", dir + "/copy.bag");  // as if killed now
  LogReadOptions options = Options();
  options.imu_topic.clear();
  auto reader = OpenBag(dir + "/copy.bag", options);
  LogMessage m;
  std::size_t scans = 0;
  while (reader->Next(&m)) ++scans;
  ASSERT_NE(reader->recovery(), nullptr);
  EXPECT_NE(reader->recovery()->damage.find("no index"), std::string::npos);
  EXPECT_GT(scans, 5u);
}

TEST(BagReader, BagCutBeforeItsFirstScanNamesTheMissingTopic) {
  const std::string path = testing::ScratchDir("bag_cut_early") + "/cut.bag";
  WriteRecording(path, PointTimeConvention::kVelodyne, 200);
  std::filesystem::resize_file(path, 4200);  // the bag header and a few bytes of a chunk
  const std::string why = OpenError(path, Options());
  EXPECT_NE(why.find(path), std::string::npos) << why;
  EXPECT_NE(why.find("no topic '/points'"), std::string::npos) << why;
}

TEST(BagReader, NotABagIsAnError) {
  const std::string path = testing::ScratchDir("bag_text") + "/text.bag";
  { std::ofstream(path) << "hello, not a bag\n"; }
  EXPECT_NE(OpenError(path, Options()).find(path), std::string::npos);
}

TEST(BagReader, MissingTopicListsTheTopicsThatExist) {
  const std::string path = testing::ScratchDir("bag_missing_topic") + "/a.bag";
  WriteRecording(path, PointTimeConvention::kVelodyne, 10);
  LogReadOptions options = Options();
  options.lidar_topic = "/velodyne_points";
  const std::string why = OpenError(path, options);
  EXPECT_NE(why.find("'/velodyne_points'"), std::string::npos) << why;
  EXPECT_NE(why.find("/imu (sensor_msgs/Imu)"), std::string::npos) << why;
  EXPECT_NE(why.find("/points (sensor_msgs/PointCloud2)"), std::string::npos) << why;
  options = Options();
  options.imu_topic = "/imu/data";
  EXPECT_NE(OpenError(path, options).find("'/imu/data'"), std::string::npos);
}

TEST(BagReader, TopicOfTheWrongTypeIsAnError) {
  const std::string path = testing::ScratchDir("bag_wrong_type") + "/a.bag";
  WriteRecording(path, PointTimeConvention::kVelodyne, 10);
  LogReadOptions options = Options();
  options.lidar_topic = "/imu";
  const std::string why = OpenError(path, options);
  EXPECT_NE(why.find("has type sensor_msgs/Imu, expected sensor_msgs/PointCloud2"),
            std::string::npos)
      << why;
}

}  // namespace
}  // namespace hylo::logs
