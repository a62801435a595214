#include "hylo/logs/scan_folder.h"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "hylo/io/cloud_io.h"
#include "test_data.h"

namespace hylo::logs {
namespace {

void Write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A scan whose first point's x equals `tag`, so the reading order can be checked.
void WriteScan(const std::string& path, double tag, bool with_nan = false) {
  io::CloudFile cloud;
  cloud.positions = {{tag, 1, 2}, {3, 4, 5}};
  cloud.intensity = {7.f, 8.f};
  if (with_nan) {
    cloud.positions.push_back({std::numeric_limits<double>::quiet_NaN(), 0, 0});
    cloud.intensity.push_back(0.f);
  }
  io::WriteCloud(path, cloud);
}

std::vector<LogMessage> ReadAll(LogReader* reader) {
  std::vector<LogMessage> messages;
  LogMessage m;
  while (reader->Next(&m)) messages.push_back(m);
  return messages;
}

TEST(ScanFolder, SortsByNumberAndStampsFromTum) {
  const std::string dir = hylo::testing::ScratchDir("folder_tum");
  WriteScan(dir + "/scan_10.pcd", 10, /*with_nan=*/true);
  WriteScan(dir + "/scan_2.pcd", 2);
  WriteScan(dir + "/scan_1.pcd", 1);
  std::string tum;
  for (int k = 0; k <= 10; ++k) tum += std::to_string(100 + k) + ".5 " + std::to_string(k) + " 0 0 0 0 0 1\n";
  Write(dir + "/poses.txt", tum);
  auto reader = OpenScanFolder(dir, LogReadOptions{});
  EXPECT_EQ(reader->time_convention(), PointTimeConvention::kNone);
  const std::vector<LogMessage> messages = ReadAll(reader.get());
  ASSERT_EQ(messages.size(), 3u);
  const double tags[3] = {1, 2, 10};
  for (int i = 0; i < 3; ++i) {
    const LidarScan& scan = messages[i].scan;
    EXPECT_EQ(messages[i].kind, LogMessage::Kind::kScan);
    EXPECT_EQ(scan.points[0].position_lidar.x(), tags[i]);
    EXPECT_EQ(scan.t_ns, (100 + static_cast<int64_t>(tags[i])) * 1000000000 + 500000000);
    EXPECT_EQ(scan.end_t_ns, scan.t_ns);
    for (const auto& p : scan.points) EXPECT_EQ(p.offset_ns, 0);
    EXPECT_EQ(scan.points[1].intensity, 8.f);
  }
  EXPECT_EQ(reader->counters().scan_messages, 3u);
  EXPECT_EQ(reader->counters().dropped_non_finite_points, 1u);
  std::vector<std::size_t> positions;
  const std::vector<io::StampedPose> poses = ReadScanFolderPoses(dir, &positions);
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(positions, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(poses[2].position.x(), 10.0);
  EXPECT_EQ(poses[2].t_ns, messages[2].scan.t_ns);
}

TEST(ScanFolder, KittiBinWithTimesAndAMissingPose) {
  const std::string dir = hylo::testing::ScratchDir("folder_kitti");
  for (int k = 0; k < 3; ++k) WriteScan(dir + "/00000" + std::to_string(k) + ".bin", k);
  Write(dir + "/poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 1 0 1 0 0 0 0 1 0\n");
  Write(dir + "/times.txt", "0.0\n0.103\n0.2071\n");
  const ScanFolderDescription d = DescribeScanFolder(dir);
  EXPECT_EQ(d.scan_count, 3u);
  EXPECT_EQ(d.format, "kitti_bin");
  EXPECT_EQ(d.pose_kind, ScanPoseFileKind::kKitti);
  EXPECT_EQ(d.point_fields, (std::vector<std::string>{"x", "y", "z", "intensity"}));
  EXPECT_EQ(d.scans_with_pose, 2u);
  EXPECT_EQ(d.scans_without_pose, 1u);
  EXPECT_DOUBLE_EQ(d.time_span_s, 0.2071);
  const auto messages = ReadAll(OpenScanFolder(dir, LogReadOptions{}).get());
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_EQ(messages[1].scan.t_ns, 103000000);
}

TEST(ScanFolder, BalmBlocksBelongToTheNumberInTheName) {
  const std::string dir = hylo::testing::ScratchDir("folder_balm");
  WriteScan(dir + "/full1.pcd", 1);
  WriteScan(dir + "/full2.pcd", 2);
  std::string csv;
  for (int k = 0; k < 3; ++k) {
    csv += "1,0,0," + std::to_string(k) + ",\n0,1,0,0,\n0,0,1,0,\n0,0,0,1630577758." +
           std::to_string(k) + "00001,\n";
  }
  Write(dir + "/poses.csv", csv);
  std::vector<std::size_t> positions;
  const std::vector<io::StampedPose> poses = ReadScanFolderPoses(dir, &positions);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].position.x(), 1.0);  // block 1, not block 0
  EXPECT_EQ(poses[1].t_ns, 1630577758200001000);
  EXPECT_TRUE(poses[1].orientation.isApprox(Eigen::Quaterniond::Identity()));
  Write(dir + "/poses.csv", "1,0,0,0\n0,1,0,0\n0,0,1,0\n0,0,1,5\n");
  try {
    IndexScanFolder(dir);
    ADD_FAILURE() << "4th row with a 1 accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("line 4"), std::string::npos) << e.what();
  }
}

TEST(ScanFolder, NoPoseFileUsesTheDefaultPeriod) {
  const std::string dir = hylo::testing::ScratchDir("folder_none");
  WriteScan(dir + "/a.ply", 0);
  WriteScan(dir + "/b.ply", 1);
  const ScanFolderDescription d = DescribeScanFolder(dir);
  EXPECT_EQ(d.pose_kind, ScanPoseFileKind::kNone);
  EXPECT_EQ(d.scans_without_pose, 2u);
  const auto messages = ReadAll(OpenScanFolder(dir, LogReadOptions{}).get());
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[1].scan.t_ns, kDefaultScanPeriodNs);
  EXPECT_EQ(messages[1].scan.points[0].position_lidar.x(), 1.f);
}

TEST(ScanFolder, Errors) {
  const std::string dir = hylo::testing::ScratchDir("folder_errors");
  EXPECT_THROW(IndexScanFolder(dir + "/absent"), std::runtime_error);
  EXPECT_THROW(IndexScanFolder(dir), std::runtime_error);  // no scans
  WriteScan(dir + "/1.pcd", 1);
  WriteScan(dir + "/2.ply", 2);
  EXPECT_THROW(IndexScanFolder(dir), std::runtime_error);  // mixed formats
  std::filesystem::remove(dir + "/2.ply");
  WriteScan(dir + "/5.pcd", 5);
  Write(dir + "/poses.txt", "0.1 0 0 0 0 0 0 1\n0.2 0 0 0 0 0 0 1\n");  // rows 0, 1 only
  EXPECT_EQ(DescribeScanFolder(dir).scans_without_time, 1u);
  EXPECT_THROW(OpenScanFolder(dir, LogReadOptions{}), std::runtime_error);  // 5.pcd unstamped
  Write(dir + "/poses.txt", "0.1 0 0 0 0 0 0\n");
  EXPECT_THROW(IndexScanFolder(dir), std::runtime_error);  // neither TUM nor KITTI
  std::filesystem::remove(dir + "/poses.txt");
  LogReadOptions options;
  options.time_convention = PointTimeConvention::kVelodyne;
  EXPECT_THROW(OpenScanFolder(dir, options), std::runtime_error);
}

TEST(ScanFolder, RealBalmFolder) {
  HYLO_REQUIRE_DATA("balm_scans/poses.csv");
  const std::string dir = hylo::testing::DataPath("balm_scans");
  const ScanFolderDescription d = DescribeScanFolder(dir);
  EXPECT_EQ(d.scan_count, 20u);
  EXPECT_EQ(d.pose_kind, ScanPoseFileKind::kBalm);
  EXPECT_EQ(d.scans_with_pose, 20u);
  EXPECT_EQ(d.encoding, "binary");
  EXPECT_GT(d.time_span_s, 9.0);  // 20 scans at 2 Hz: 19 intervals of ~0.5 s
  EXPECT_LT(d.time_span_s, 10.5);
  EXPECT_EQ(d.point_fields.front(), "x");
  EXPECT_EQ(d.point_fields[4], "normal_x");
  const std::vector<io::StampedPose> poses = ReadScanFolderPoses(dir);
  ASSERT_EQ(poses.size(), 20u);
  for (std::size_t k = 1; k < poses.size(); ++k) {
    EXPECT_GT(poses[k].t_ns, poses[k - 1].t_ns);
    EXPECT_LT((poses[k].position - poses[k - 1].position).norm(), 2.0);  // a walked path
  }
  auto reader = OpenScanFolder(dir, LogReadOptions{});
  LogMessage m;
  ASSERT_TRUE(reader->Next(&m));
  EXPECT_EQ(m.scan.t_ns, poses[0].t_ns);
  EXPECT_EQ(m.scan.points.size() + reader->counters().dropped_non_finite_points,
            d.first_scan_points);
  EXPECT_GT(m.scan.points.size(), 50000u);
}

}  // namespace
}  // namespace hylo::logs
