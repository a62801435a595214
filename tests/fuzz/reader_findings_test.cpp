// What the fuzz targets (and reading the readers while writing them) found, each pinned to the
// answer it gets now: a clear one-line error naming the file, or the documented result. The
// inputs themselves are replayed through the targets from regressions/ (fuzz_replay_*).

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/config/run_config.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/json.h"
#include "hylo/logs/pointcloud2.h"
#include "hylo/logs/ros_bridge.h"
#include "hylo/logs/scan_folder.h"
#include "hylo/io/trajectory_io.h"
#include "hylo/localization/pose_guess.h"
#include "test_data.h"

namespace hylo {
namespace {

using logs::PointTimeConvention;

std::string WriteFile(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The message of what `read` throws (of type E); "" when it does not throw.
template <class E, class F>
std::string ErrorOf(F read) {
  try {
    read();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

void ExpectOneLineNaming(const std::string& error, const std::string& name,
                         const std::string& reason) {
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_NE(error.find(name), std::string::npos) << error;
  EXPECT_NE(error.find(reason), std::string::npos) << error;
}

TEST(ReaderFindings, PoseGuessErrorStaysOnOneLineWhateverTheTextsLineBreaks) {
  const std::string error = ErrorOf<std::invalid_argument>(
      [] { localization::ParsePoseGuess("0 -1 0 1\nq 0 0 2\n0 0 1 3\n0 0 0 1"); });
  ExpectOneLineNaming(error, "pose guess", "'q' is not a finite number");
}

TEST(ReaderFindings, SecondsWithAnExponentBeyondInt64NanosecondsAreRefused) {
  int64_t t_ns = 0;
  EXPECT_FALSE(io::ParseSecondsToNs("1e300", &t_ns));  // was llround's unspecified INT64_MIN
  EXPECT_FALSE(io::ParseSecondsToNs("-9.3e9", &t_ns));
  ASSERT_TRUE(io::ParseSecondsToNs("9.1e9", &t_ns));
  EXPECT_EQ(t_ns, 9'100'000'000'000'000'000);
}

LidarScan TwoPointScan() {
  LidarScan scan;
  scan.t_ns = 1'600'000'000'000'000'000;
  for (int i = 0; i < 2; ++i) {
    ScanPoint p;
    p.position_lidar = {1.f + i, 2.f, 3.f};
    p.offset_ns = 1000 * i;
    scan.points.push_back(p);
  }
  scan.end_t_ns = scan.t_ns + 1000;
  return scan;
}

// Sets the per-point time field of point `i` (float32 or float64 as the layout has it).
void SetTime(logs::PointCloud2Message* cloud, const char* field, std::size_t i, double value) {
  for (const logs::PointFieldInfo& f : cloud->fields) {
    if (f.name != field) continue;
    uint8_t* at = cloud->data.data() + i * cloud->point_step + f.offset;
    if (f.datatype == logs::kFloat64) {
      std::memcpy(at, &value, sizeof(value));
    } else {
      const float v = static_cast<float>(value);
      std::memcpy(at, &v, sizeof(v));
    }
  }
}

TEST(ReaderFindings, PointCloud2FieldNameWithALineBreakGivesAOneLineError) {
  logs::PointCloud2Message cloud = EncodePointCloud2(TwoPointScan(), PointTimeConvention::kNone);
  cloud.fields[2].name = "z\nmore";
  const std::string error = ErrorOf<std::runtime_error>(
      [&] { DecodePointCloud2(cloud, PointTimeConvention::kAuto, nullptr); });
  ExpectOneLineNaming(error, "z?more", "no x/y/z");
}

TEST(ReaderFindings, PointCloud2WithEmptyRowsIsAnEmptyScan) {
  logs::PointCloud2Message cloud = EncodePointCloud2(TwoPointScan(), PointTimeConvention::kNone);
  cloud.width = 0;
  cloud.height = std::numeric_limits<uint32_t>::max();  // walked row by row, this took seconds
  EXPECT_TRUE(DecodePointCloud2(cloud, PointTimeConvention::kAuto, nullptr).points.empty());
}

TEST(ReaderFindings, PointCloud2RelativeTimeBeyondInt64IsDroppedAndCounted) {
  logs::PointCloud2Message cloud = EncodePointCloud2(TwoPointScan(), PointTimeConvention::kVelodyne);
  cloud.stamp_ns = 4'294'967'295'999'999'999;  // the largest ROS stamp
  SetTime(&cloud, "time", 1, 8.9e9);           // + 8.9e18 ns overflowed int64
  std::size_t dropped = 0;
  const LidarScan scan = DecodePointCloud2(cloud, PointTimeConvention::kVelodyne, &dropped);
  EXPECT_EQ(scan.points.size(), 1u);
  EXPECT_EQ(dropped, 1u);
}

TEST(ReaderFindings, PointCloud2TimesAtBothEndsOfInt64AreASpanError) {
  logs::PointCloud2Message cloud = EncodePointCloud2(TwoPointScan(), PointTimeConvention::kHesai);
  SetTime(&cloud, "timestamp", 0, -9.0e9);  // their difference overflowed int64
  SetTime(&cloud, "timestamp", 1, 9.0e9);
  const std::string error = ErrorOf<std::runtime_error>(
      [&] { DecodePointCloud2(cloud, PointTimeConvention::kHesai, nullptr); });
  ExpectOneLineNaming(error, "span", "int32");
}

TEST(ReaderFindings, BagMessageArrayLongerThanTheMessageIsRefusedBeforeAllocating) {
  logs::PointCloud2Message cloud = EncodePointCloud2(TwoPointScan(), PointTimeConvention::kNone);
  const sensor_msgs::PointCloud2 msg = logs::ros_bridge::ToRos(std::move(cloud));
  std::vector<uint8_t> bytes(ros::serialization::serializationLength(msg));
  ros::serialization::OStream out(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::serialize(out, msg);
  // The data array's length prefix sits before its 32 bytes and the is_dense byte. ROS's own
  // stream would allocate (and zero) 4 GiB before noticing the message ends.
  const uint32_t huge = 0xFFFFFFF0u;
  std::memcpy(bytes.data() + bytes.size() - 1 - 32 - 4, &huge, sizeof(huge));
  const std::string error = ErrorOf<ros::serialization::StreamOverrunException>(
      [&] { logs::ros_bridge::Deserialize<sensor_msgs::PointCloud2>(bytes.data(), bytes.size()); });
  EXPECT_NE(error.find("announces 4294967280 elements"), std::string::npos) << error;
}

class ReaderFindingsFiles : public ::testing::Test {
 protected:
  std::string dir_ = testing::ScratchDir("reader_findings");
};

const char kXyzHeader[] = "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n";

TEST_F(ReaderFindingsFiles, PcdCountsWhoseRecordOverflowsAreErrors) {
  const std::string path =
      WriteFile(dir_, "count.pcd",
                "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 4611686018427387904\n"
                "WIDTH 1\nDATA binary\nabcdefghijkl");  // point_step wrapped to 8 (or 0: SIGFPE)
  ExpectOneLineNaming(ErrorOf<std::runtime_error>([&] { io::ReadCloud(path); }), path,
                      "COUNT 4611686018427387904, more bytes than a point can hold");
}

TEST_F(ReaderFindingsFiles, PcdWidthTimesHeightOverflowIsAnError) {
  const std::string path = WriteFile(dir_, "wh.pcd",
                                     std::string(kXyzHeader) +
                                         "WIDTH 4294967296\nHEIGHT 4294967296\n"
                                         "DATA ascii\n");  // was 0 points
  ExpectOneLineNaming(ErrorOf<std::runtime_error>([&] { io::ReadCloudInfo(path); }), path,
                      "WIDTH * HEIGHT overflows");
}

TEST_F(ReaderFindingsFiles, PcdAsciiCountBeyondTheBodyIsTruncatedNotAnAllocation) {
  const std::string path = WriteFile(dir_, "ascii.pcd",
                                     "VERSION .7\nFIELDS x y z w\nSIZE 4 4 4 4\nTYPE F F F F\n"
                                     "COUNT 1 1 1 100000000000\nWIDTH 1\nDATA ascii\n1 2 3 4\n");
  ExpectOneLineNaming(ErrorOf<std::runtime_error>([&] { io::ReadCloud(path); }), path, "truncated");
}

TEST_F(ReaderFindingsFiles, PcdAsciiWithoutPointsIgnoresItsCounts) {
  // The same header with WIDTH 0 once sized a buffer of 1e11 values for the points it lacks.
  const std::string path = WriteFile(dir_, "ascii_empty.pcd",
                                     "VERSION .7\nFIELDS x y z w\nSIZE 4 4 4 4\nTYPE F F F F\n"
                                     "COUNT 1 1 1 100000000000\nWIDTH 0\nDATA ascii\n1 2 3 4\n");
  EXPECT_TRUE(io::ReadCloud(path).positions.empty());
}

TEST_F(ReaderFindingsFiles, PcdCompressedBlockCannotAnnounceMoreThanLzfExpandsTo) {
  std::string body(8, '\0');
  const uint32_t compressed = 16, uncompressed = 3'000'000'000u;  // 1e9 points of 3 bytes
  std::memcpy(body.data(), &compressed, 4);
  std::memcpy(body.data() + 4, &uncompressed, 4);
  body += std::string(16, '\x01');
  const std::string path = WriteFile(dir_, "lzf.pcd",
                                     "VERSION .7\nFIELDS x y z\nSIZE 1 1 1\nTYPE U U U\n"
                                     "WIDTH 1000000000\nHEIGHT 1\nDATA binary_compressed\n" +
                                         body);
  ExpectOneLineNaming(ErrorOf<std::runtime_error>([&] { io::ReadCloud(path); }), path,
                      "16 LZF bytes cannot expand to the 3000000000 bytes");
}

TEST_F(ReaderFindingsFiles, JsonNumberBeyondDoubleIsAnErrorNamingTheFile) {
  // nlohmann reports it as out_of_range, not as a parse error: it once escaped the reader.
  const std::string path = WriteFile(dir_, "overflow.json", "{\"a\": 22222222E2222222}\n");
  ExpectOneLineNaming(ErrorOf<std::runtime_error>([&] { io::ReadJsonFile(path); }), path,
                      "number overflow parsing '22222222E2222222'");
}

const char kPlyXyz[] = "property float x\nproperty float y\nproperty float z\n";

TEST_F(ReaderFindingsFiles, PlyElementWithoutPropertiesTakesNoBytes) {
  const std::string path = WriteFile(dir_, "empty_element.ply",
                                     "ply\nformat ascii 1.0\nelement camera 100000000000\n"
                                     "element vertex 1\n" +
                                         std::string(kPlyXyz) + "end_header\n1 2 3\n");
  const io::CloudFile cloud = io::ReadCloud(path);  // was 1e11 empty iterations
  ASSERT_EQ(cloud.positions.size(), 1u);
  EXPECT_EQ(cloud.positions[0], Eigen::Vector3d(1, 2, 3));
}

TEST_F(ReaderFindingsFiles, PlyListLengthBeyondTheBodyIsAnError) {
  const std::string path = WriteFile(
      dir_, "list.ply",
      "ply\nformat ascii 1.0\nelement vertex 1\n" + std::string(kPlyXyz) +
          "property list uchar int idx\nend_header\n1 2 3 1e300\n");  // 1e300 -> size_t was UB
  ExpectOneLineNaming(ErrorOf<std::runtime_error>([&] { io::ReadCloud(path); }), path,
                      "corrupt: list length");
}

TEST_F(ReaderFindingsFiles, PlyNegativeElementCountIsAnError) {
  const std::string path = WriteFile(
      dir_, "negative.ply",
      "ply\nformat ascii 1.0\nelement vertex -1\n" + std::string(kPlyXyz) + "end_header\n");
  ExpectOneLineNaming(ErrorOf<std::runtime_error>([&] { io::ReadCloudInfo(path); }), path,
                      "bad element count -1");
}

TEST_F(ReaderFindingsFiles, ScanFolderIndexTooLargeToStampAtTenHertzHasNoStamp) {
  io::CloudFile cloud;
  cloud.positions = {{1, 2, 3}};
  io::WriteCloud(dir_ + "/scan_123456789012.pcd", cloud);  // x 1e8 ns overflowed int64
  const logs::ScanFolderIndex index = logs::IndexScanFolder(dir_);
  ASSERT_EQ(index.scans.size(), 1u);
  EXPECT_FALSE(index.scans[0].has_time);
  ExpectOneLineNaming(
      ErrorOf<std::runtime_error>([&] { logs::OpenScanFolder(dir_, logs::LogReadOptions{}); }),
      "scan_123456789012.pcd", "beyond the int64 ns range");
}

TEST_F(ReaderFindingsFiles, BalmPoseWithANonFiniteNumberIsAnError) {
  io::CloudFile cloud;
  cloud.positions = {{1, 2, 3}};
  io::WriteCloud(dir_ + "/scan0.pcd", cloud);
  const std::string poses =
      WriteFile(dir_, "poses.csv", "1,0,0,inf\n0,1,0,0\n0,0,1,0\n0,0,0,1.5\n");
  ExpectOneLineNaming(ErrorOf<std::runtime_error>([&] { logs::IndexScanFolder(dir_); }), poses,
                      "line 1: 'inf' is not a finite number");
}

TEST(ReaderFindings, ConfigurationKeyThatIsAListIsAConfigError) {
  for (const char* text : {"{[1]: 2}\n", "imu: {[a]: 1}\n"}) {
    const std::string error = ErrorOf<config::ConfigError>(
        [&] { config::ParseRunConfig(text, "odd_keys.yaml"); });  // was YAML::BadConversion
    ExpectOneLineNaming(error, "odd_keys.yaml", "a key that is a list");
  }
}

// A key given twice was silently resolved to one of its values; and an alias inside itself
// must not send the duplicate check round in circles.
TEST(ReaderFindings, ConfigurationKeyGivenTwiceIsAConfigError) {
  ExpectOneLineNaming(ErrorOf<config::ConfigError>([] {
                        config::ParseRunConfig("lidar:\n  topic: /a\n  topic: /b\n", "twice.yaml");
                      }),
                      "twice.yaml", "lidar.topic: the key is given twice (line 2 and line 3)");
  ExpectOneLineNaming(
      ErrorOf<config::ConfigError>([] { config::ParseRunConfig("a: &x [*x]\n", "alias.yaml"); }),
      "alias.yaml", "unknown key");
}

}  // namespace
}  // namespace hylo
