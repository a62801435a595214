// What the bag_records fuzz target found in the record-by-record reading of bags whose index
// rosbag cannot read, each pinned to the answer it gets now, through the public readers. The
// inputs themselves are replayed through the target from regressions/bag_records
// (fuzz_replay_bag_records).

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "hylo/logs/bag_reader.h"
#include "hylo/logs/bag_writer.h"
#include "test_data.h"

namespace hylo::logs {
namespace {

constexpr int kMessages = 5;  // four IMU samples and a scan

std::string FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// What OpenBag throws for `path` ("" when it opens the bag).
std::string OpenError(const std::string& path) {
  try {
    OpenBag(path, LogReadOptions());
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

class BagRecordFindings : public ::testing::Test {
 protected:
  /// A small bag as a killed recording leaves it: index_pos still 0, no index at the end.
  std::string UnindexedBag(BagCompression compression) {
    const std::string path = dir_ + "/whole.bag";
    {
      BagWriter writer(path, compression);
      LidarScan scan;
      scan.t_ns = 1'700'000'000'000'000'000;
      for (int i = 0; i < 4; ++i) {
        ScanPoint p;
        p.position_lidar = {1.0f + i, 2.0f, -0.5f * i};
        p.offset_ns = 1'000'000 * i;
        scan.points.push_back(p);
      }
      scan.end_t_ns = scan.t_ns + scan.points.back().offset_ns;
      for (int i = 0; i < 4; ++i) {
        ImuSample imu;
        imu.t_ns = scan.t_ns + 2'000'000LL * i;
        imu.accel_imu = {0.01 * i, 0.0, 9.81};
        writer.WriteImu("/imu", imu, "imu");
        if (i == 1) writer.WriteScan("/points", scan, PointTimeConvention::kVelodyne, "lidar");
      }
    }
    std::string bytes = FileBytes(path);
    const std::size_t field = bytes.find("index_pos=") + 10;
    uint64_t index_pos = 0;
    std::memcpy(&index_pos, bytes.data() + field, sizeof(index_pos));
    bytes.resize(index_pos);
    std::memset(&bytes[field], 0, sizeof(index_pos));
    return bytes;
  }

  std::string Write(const std::string& bytes) {
    const std::string path = dir_ + "/damaged.bag";
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    return path;
  }

  std::string dir_ = testing::ScratchDir("bag_record_findings");
};

// The walker sized the header buffer from the length field before checking it: 4 GiB.
TEST_F(BagRecordFindings, RecordHeaderAnnouncingGigabytesStopsTheWalkAndKeepsWhatCameBefore) {
  const std::string huge("\xf0\xff\xff\xff", 4);
  const BagDescription d = DescribeBag(Write(UnindexedBag(BagCompression::kNone) + huge));
  ASSERT_TRUE(d.recovery.has_value());
  EXPECT_EQ(d.message_count, kMessages);
  EXPECT_EQ(d.recovery->stop_reason, "a record header is corrupt (too long)");
  EXPECT_EQ(d.recovery->unreadable_bytes, 4u);
}

// roslz4 asks for more output room, without writing, for a block it cannot decode while the
// room is smaller than the stream's largest block; the decoder loop asked it forever.
TEST_F(BagRecordFindings, Lz4BlockTheDecoderCannotReadStopsTheWalk) {
  std::string bytes = UnindexedBag(BagCompression::kLz4);
  const std::size_t frame = bytes.find("\x04\x22\x4d\x18");
  ASSERT_NE(frame, std::string::npos);
  // The frame header (7 bytes) and the first block's length (4), then its data.
  for (std::size_t i = frame + 11; i < frame + 11 + 64; ++i) bytes[i] = '\xff';
  const BagDescription d = DescribeBag(Write(bytes));
  ASSERT_TRUE(d.recovery.has_value());
  EXPECT_EQ(d.message_count, 0u);
  EXPECT_NE(d.recovery->stop_reason.find("lz4: corrupt data"), std::string::npos)
      << d.recovery->stop_reason;
}

// The decoder allocated (and zeroed) the chunk's announced size up front: 2 GB for a corrupt
// size field. The size now only caps the output; the chunk is read for what it holds.
TEST_F(BagRecordFindings, ChunkAnnouncingGigabytesIsReadForWhatItHolds) {
  std::string bytes = UnindexedBag(BagCompression::kLz4);
  const std::size_t field = bytes.find("size=");  // the chunk header's, the first record's
  ASSERT_NE(field, std::string::npos);
  const uint32_t two_gb = 0x7ffffff0u;
  std::memcpy(&bytes[field + 5], &two_gb, sizeof(two_gb));
  const BagDescription d = DescribeBag(Write(bytes));
  ASSERT_TRUE(d.recovery.has_value());
  EXPECT_EQ(d.message_count, kMessages);
}

TEST_F(BagRecordFindings, MessageDefinitionMismatchErrorNamesTheBag) {
  std::string bytes = UnindexedBag(BagCompression::kNone);
  const std::size_t md5 = bytes.find("md5sum=1158d486dd51d683ce2f1be655c3c181");
  ASSERT_NE(md5, std::string::npos);
  bytes[md5 + 7] = '0';
  const std::string path = Write(bytes);
  const std::string error = OpenError(path);
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("md5sum 0158d486"), std::string::npos) << error;
}

TEST_F(BagRecordFindings, TopicWithALineBreakGivesAOneLineError) {
  std::string bytes = UnindexedBag(BagCompression::kNone);
  const std::size_t topic = bytes.find("topic=/imu");
  ASSERT_NE(topic, std::string::npos);
  bytes[topic + 8] = '\n';  // "/i\nu"
  const std::string path = Write(bytes);
  const std::string error = OpenError(path);
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("/i?u (sensor_msgs/Imu)"), std::string::npos) << error;
}

}  // namespace
}  // namespace hylo::logs
