// ROS 2 messages in CDR: the reader's alignment and byte-order rules on hand-made bytes, the
// messages hylo writes read back field for field, a Livox CustomMsg read as its driver's
// PointCloud2, and bytes that do not hold a message refused before anything is allocated.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "cdr_messages.h"
#include "cdr_reader.h"
#include "cdr_writer.h"
#include "hylo/logs/pointcloud2.h"

namespace hylo::logs::detail {
namespace {

constexpr int64_t kStamp = 1700000000123456789;

std::vector<uint8_t> Bytes(std::initializer_list<int> values) {
  return std::vector<uint8_t>(values.begin(), values.end());
}

TEST(CdrReader, AlignsEachPrimitiveToItsSizeFromTheEndOfTheHeader) {
  // u8 1, (pad 1) u16 0x0203, u32 4, (pad 0) f64 at offset 8, a string "ab".
  std::vector<uint8_t> b = Bytes({0, 1, 0, 0, 1, 0, 3, 2, 4, 0, 0, 0});
  double d = 2.5;
  const std::size_t at = b.size();
  b.resize(at + 8);
  std::memcpy(&b[at], &d, 8);
  for (int v : {3, 0, 0, 0, int{'a'}, int{'b'}, 0}) b.push_back(static_cast<uint8_t>(v));
  CdrReader in(b.data(), b.size());
  EXPECT_EQ(in.Read<uint8_t>(), 1);
  EXPECT_EQ(in.Read<uint16_t>(), 0x0203);
  EXPECT_EQ(in.Read<uint32_t>(), 4u);
  EXPECT_EQ(in.Read<double>(), 2.5);
  EXPECT_EQ(in.ReadString(), "ab");
  EXPECT_EQ(in.remaining(), 0u);
}

TEST(CdrReader, ReadsBigEndianAndCdr2) {
  const std::vector<uint8_t> big = Bytes({0, 0, 0, 0, 0x12, 0x34, 0, 0, 0, 0, 0, 7});
  CdrReader be(big.data(), big.size());
  EXPECT_EQ(be.Read<uint16_t>(), 0x1234);
  EXPECT_EQ(be.Read<uint32_t>(), 7u);
  // Plain CDR2 (0x0007): an 8-byte value after a u32 is aligned to 4, not 8.
  std::vector<uint8_t> cdr2 = Bytes({0, 7, 0, 0, 1, 0, 0, 0});
  const int64_t v = -5;
  cdr2.resize(16);
  std::memcpy(&cdr2[8], &v, 8);
  CdrReader in(cdr2.data(), cdr2.size());
  EXPECT_EQ(in.Read<uint32_t>(), 1u);
  EXPECT_EQ(in.Read<int64_t>(), -5);
}

TEST(CdrReader, RefusesWhatDoesNotHoldAMessage) {
  const std::vector<uint8_t> short_header = Bytes({0, 1});
  EXPECT_THROW(CdrReader(short_header.data(), short_header.size()), CdrError);
  const std::vector<uint8_t> xml = Bytes({'<', '?', 'x', 'm'});
  try {
    CdrReader in(xml.data(), xml.size());
    FAIL();
  } catch (const CdrError& e) {
    EXPECT_NE(std::string(e.what()).find("unsupported CDR encapsulation"), std::string::npos);
  }
  // A sequence announcing 4 G elements in a 12-byte message: refused, nothing allocated.
  const std::vector<uint8_t> huge = Bytes({0, 1, 0, 0, 0xff, 0xff, 0xff, 0xff, 1, 2, 3, 4});
  CdrReader in(huge.data(), huge.size());
  EXPECT_THROW(in.ReadSequenceLength(1), CdrError);
  // A string running past the end.
  const std::vector<uint8_t> cut = Bytes({0, 1, 0, 0, 9, 0, 0, 0, 'a', 'b'});
  CdrReader s(cut.data(), cut.size());
  EXPECT_THROW(s.ReadString(), CdrError);
}

PointCloud2Message SmallCloud() {
  LidarScan scan;
  scan.t_ns = kStamp;
  for (int i = 0; i < 5; ++i) {
    ScanPoint p;
    p.position_lidar = {1.0f * i, -0.5f * i, 0.25f};
    p.intensity = 7.0f * i;
    p.ring = static_cast<uint16_t>(i);
    p.offset_ns = 1000000 * i;
    scan.points.push_back(p);
  }
  scan.end_t_ns = kStamp + 4000000;
  PointCloud2Message cloud = EncodePointCloud2(scan, PointTimeConvention::kOuster);
  cloud.frame_id = "os_lidar";
  return cloud;
}

TEST(CdrMessages, PointCloud2RoundTripsFieldForField) {
  const PointCloud2Message cloud = SmallCloud();
  const std::vector<uint8_t> bytes = EncodeCdrPointCloud2(cloud);
  const PointCloud2Message back = DecodeCdrPointCloud2(bytes.data(), bytes.size());
  EXPECT_EQ(back.stamp_ns, cloud.stamp_ns);
  EXPECT_EQ(back.frame_id, "os_lidar");
  EXPECT_EQ(back.height, cloud.height);
  EXPECT_EQ(back.width, cloud.width);
  ASSERT_EQ(back.fields.size(), cloud.fields.size());
  for (std::size_t i = 0; i < cloud.fields.size(); ++i) {
    EXPECT_EQ(back.fields[i].name, cloud.fields[i].name);
    EXPECT_EQ(back.fields[i].datatype, cloud.fields[i].datatype);
    EXPECT_EQ(back.fields[i].offset, cloud.fields[i].offset);
    EXPECT_EQ(back.fields[i].count, cloud.fields[i].count);
  }
  EXPECT_EQ(back.point_step, cloud.point_step);
  EXPECT_EQ(back.row_step, cloud.row_step);
  EXPECT_EQ(back.data, cloud.data);
  EXPECT_EQ(back.is_dense, cloud.is_dense);
  EXPECT_EQ(back.is_bigendian, cloud.is_bigendian);
  // Every prefix of the message is refused with CdrError, never read past its end.
  for (std::size_t n = 0; n < bytes.size(); n += 7) {
    EXPECT_THROW(DecodeCdrPointCloud2(bytes.data(), n), CdrError) << n;
  }
}

TEST(CdrMessages, ImuRoundTripsAndStampsBeforeTheEpochKeepNanosecondsPositive) {
  ImuSample imu;
  imu.t_ns = kStamp;
  imu.accel_imu = {0.1, -0.2, 9.81};
  imu.gyro_imu = {0.01, 0.02, -0.03};
  std::vector<uint8_t> bytes = EncodeCdrImu(imu, "imu_link");
  ImuSample back = DecodeCdrImu(bytes.data(), bytes.size());
  EXPECT_EQ(back.t_ns, imu.t_ns);
  EXPECT_EQ(back.accel_imu, imu.accel_imu);
  EXPECT_EQ(back.gyro_imu, imu.gyro_imu);
  imu.t_ns = -1500000000;  // -1.5 s: sec -2, nanosec 500000000
  bytes = EncodeCdrImu(imu, "imu");
  CdrReader in(bytes.data(), bytes.size());
  EXPECT_EQ(in.Read<int32_t>(), -2);
  EXPECT_EQ(in.Read<uint32_t>(), 500000000u);
  EXPECT_EQ(DecodeCdrImu(bytes.data(), bytes.size()).t_ns, imu.t_ns);
  imu.t_ns = std::numeric_limits<int64_t>::max();  // past 2038: builtin_interfaces/Time overflows
  EXPECT_THROW(EncodeCdrImu(imu, "imu"), std::invalid_argument);
}

TEST(CdrMessages, LivoxCustomMsgReadsAsTheDriversPointCloud2) {
  const uint64_t timebase = 1700000000000000000;
  std::vector<LivoxCustomPoint> points(3);
  for (int i = 0; i < 3; ++i) {
    points[i].offset_time_ns = 100000 * i;
    points[i].x = 1.0f + i;
    points[i].y = 2.0f;
    points[i].z = -1.0f;
    points[i].reflectivity = static_cast<uint8_t>(10 * i);
    points[i].line = static_cast<uint8_t>(i + 1);
  }
  const std::vector<uint8_t> bytes = EncodeCdrLivoxCustom(timebase, "livox", timebase, points);
  const PointCloud2Message cloud = DecodeCdrLivoxCustom(bytes.data(), bytes.size());
  EXPECT_EQ(DetectPointTimeConvention(cloud.fields), PointTimeConvention::kLivox);
  const LidarScan scan = DecodePointCloud2(cloud, PointTimeConvention::kAuto, nullptr);
  ASSERT_EQ(scan.points.size(), 3u);
  EXPECT_EQ(scan.t_ns, static_cast<int64_t>(timebase));
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(scan.points[i].position_lidar.x(), 1.0f + i);
    EXPECT_EQ(scan.points[i].intensity, 10.0f * i);
    EXPECT_EQ(scan.points[i].ring, i + 1);
    // Absolute ns in a double: exact to 256 ns at this epoch, as the driver's own PointCloud2.
    EXPECT_NEAR(scan.points[i].offset_ns, 100000 * i, 256);
  }
}

TEST(CdrMessages, DefinitionsNameEveryTypeTheyUse) {
  const std::string cloud = Ros2MessageDefinition(kRos2CloudType);
  EXPECT_NE(cloud.find("PointField[] fields"), std::string::npos);
  EXPECT_NE(cloud.find("\nMSG: sensor_msgs/PointField\n"), std::string::npos);
  EXPECT_NE(cloud.find("\nMSG: builtin_interfaces/Time\n"), std::string::npos);
  EXPECT_NE(Ros2MessageDefinition(kRos2ImuType).find("MSG: geometry_msgs/Vector3"),
            std::string::npos);
  EXPECT_NE(Ros2MessageDefinition(kLivoxCustomType).find("MSG: livox_ros_driver2/CustomPoint"),
            std::string::npos);
  EXPECT_EQ(Ros2MessageDefinition("std_msgs/msg/String"), "");
}

}  // namespace
}  // namespace hylo::logs::detail
