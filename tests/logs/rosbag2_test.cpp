// ROS 2 recordings end to end through the public readers and writers: every format gives the
// messages a ROS1 bag gives; split recordings are merged by log time; a directory the recorder
// left without metadata.yaml, or a database cut short, is read with a warning; rosbag2's own
// zstd compression (per message, per file) is read; a Livox CustomMsg topic gives Livox scans;
// and every broken recording is refused in one line that names it.

#include <gtest/gtest.h>
#include <zstd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cdr_messages.h"
#include "hylo/logs/log_convert.h"
#include "hylo/logs/rosbag2_reader.h"
#include "hylo/logs/rosbag2_writer.h"
#include "log_samples.h"
#include "rosbag2_metadata.h"
#include "sqlite_writer.h"
#include "test_data.h"

namespace hylo::logs {
namespace {

namespace fs = std::filesystem;
using testing::ExpectSameMessages;
using testing::ReadAll;
using testing::SampleMessages;
using testing::WriteMessages;

std::string Write(const std::string& path, LogFormat format,
                  const std::vector<LogMessage>& messages) {
  auto writer = CreateLogWriter(path, format);
  WriteMessages(messages, writer.get());
  writer->Close();
  return path;
}

std::string ErrorOf(const std::string& path, const LogReadOptions& options = LogReadOptions()) {
  try {
    auto reader = OpenLog(path, options);
    ReadAll(reader.get());
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.what();
  }
  return "";
}

void WriteText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

class Rosbag2Format : public ::testing::TestWithParam<LogFormat> {};

TEST_P(Rosbag2Format, GivesTheMessagesARos1BagGives) {
  const std::string dir = hylo::testing::ScratchDir("rosbag2_formats");
  const std::vector<LogMessage> written = SampleMessages(2.0);
  const std::string reference = Write(dir + "/ref.bag", LogFormat::kRos1, written);
  const std::string path = Write(dir + "/rec", GetParam(), written);
  EXPECT_TRUE(IsRosbag2(path));
  EXPECT_TRUE(fs::exists(path + "/metadata.yaml"));
  auto reader = OpenLog(path, LogReadOptions());
  EXPECT_EQ(reader->recovery(), nullptr);
  ExpectSameMessages(ReadAll(reader.get()), ReadAll(reference));
  EXPECT_EQ(reader->counters().scan_messages, 20u);
  // The directory's metadata agrees with what the storage holds.
  const detail::Rosbag2Metadata m = detail::ReadRosbag2Metadata(path + "/metadata.yaml");
  EXPECT_EQ(m.version, 5);
  EXPECT_EQ(m.message_count, written.size());
  EXPECT_EQ(m.relative_file_paths.size(), 1u);
  EXPECT_EQ(DescribeRosbag2(path).message_count, written.size());
}

INSTANTIATE_TEST_SUITE_P(Formats, Rosbag2Format,
                         ::testing::Values(LogFormat::kSqlite3, LogFormat::kMcap,
                                           LogFormat::kMcapZstd, LogFormat::kMcapLz4),
                         [](const auto& info) {
                           std::string name = ToString(info.param);
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(Rosbag2, WriterRefusesToOverwriteARecordingAndLeavesNothingWhenAbandoned) {
  const std::string dir = hylo::testing::ScratchDir("rosbag2_writer");
  Write(dir + "/rec", LogFormat::kMcap, SampleMessages(0.2));
  EXPECT_THROW(CreateLogWriter(dir + "/rec", LogFormat::kMcap), std::runtime_error);
  for (const LogFormat f : {LogFormat::kSqlite3, LogFormat::kMcapZstd}) {
    {
      auto writer = CreateLogWriter(dir + "/abandoned", f);
      WriteMessages(SampleMessages(0.2), writer.get());
    }  // destroyed before Close(): a failed run
    EXPECT_FALSE(fs::exists(dir + "/abandoned")) << ToString(f);
  }
}

/// A recording split into two files whose time ranges interleave, with the metadata a
/// recorder writes (version 4, no per-file list, as the real split bags have).
std::string SplitRecording(const std::string& dir, LogFormat format) {
  const std::vector<LogMessage> all = SampleMessages(2.0);
  std::vector<LogMessage> even, odd;
  for (std::size_t i = 0; i < all.size(); ++i) (i % 2 == 0 ? even : odd).push_back(all[i]);
  const std::string bag = dir + "/split";
  fs::create_directories(bag);
  const std::string ext = format == LogFormat::kSqlite3 ? ".db3" : ".mcap";
  int index = 0;
  for (const auto* part : {&even, &odd}) {
    const std::string one = Write(dir + "/part" + std::to_string(index), format, *part);
    fs::rename(one + "/part" + std::to_string(index) + "_0" + ext,
               bag + "/split_" + std::to_string(index) + ext);
    ++index;
  }
  WriteText(bag + "/metadata.yaml",
            "rosbag2_bagfile_information:\n  version: 4\n  storage_identifier: " +
                std::string(format == LogFormat::kSqlite3 ? "sqlite3" : "mcap") +
                "\n  relative_file_paths: [split_0" + ext + ", split_1" + ext +
                "]\n  duration: {nanoseconds: 0}\n  starting_time: {nanoseconds_since_epoch: 0}\n"
                "  message_count: 0\n  topics_with_message_count: []\n"
                "  compression_format: ''\n  compression_mode: ''\n");
  return bag;
}

TEST(Rosbag2, SplitFilesAreMergedByLogTime) {
  for (const LogFormat format : {LogFormat::kSqlite3, LogFormat::kMcapZstd}) {
    SCOPED_TRACE(ToString(format));
    const std::string dir = hylo::testing::ScratchDir("rosbag2_split");
    const std::string bag = SplitRecording(dir, format);
    const std::string reference = Write(dir + "/ref.bag", LogFormat::kRos1, SampleMessages(2.0));
    ExpectSameMessages(ReadAll(bag), ReadAll(reference));
    const Rosbag2Description d = DescribeRosbag2(bag);
    EXPECT_EQ(d.files.size(), 2u);
    EXPECT_EQ(d.message_count, SampleMessages(2.0).size());
    // Without metadata.yaml (the recorder was killed): the files in split order, a warning.
    fs::remove(bag + "/metadata.yaml");
    auto reader = OpenLog(bag, LogReadOptions());
    ASSERT_NE(reader->recovery(), nullptr);
    EXPECT_NE(reader->recovery()->damage.find("no metadata.yaml"), std::string::npos);
    ExpectSameMessages(ReadAll(reader.get()), ReadAll(reference));
  }
}

TEST(Rosbag2, ADatabaseCutShortIsReadToItsLastReadableMessage) {
  const std::string dir = hylo::testing::ScratchDir("rosbag2_cut_db");
  const std::vector<LogMessage> written = SampleMessages(3.0, 400);
  const std::string bag = Write(dir + "/rec", LogFormat::kSqlite3, written);
  const std::string db = bag + "/rec_0.db3";
  const std::vector<LogMessage> all = ReadAll(bag);
  for (const double fraction : {0.3, 0.6, 0.9}) {
    SCOPED_TRACE(fraction);
    const auto size = fs::file_size(db);
    fs::copy_file(db, dir + "/copy.db3", fs::copy_options::overwrite_existing);
    fs::resize_file(dir + "/copy.db3", static_cast<uintmax_t>(size * fraction));
    std::unique_ptr<LogReader> reader;
    try {
      reader = OpenLog(dir + "/copy.db3", LogReadOptions());
    } catch (const std::runtime_error& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    ASSERT_NE(reader->recovery(), nullptr);
    EXPECT_NE(reader->recovery()->damage.find("database cut short"), std::string::npos);
    const std::vector<LogMessage> read = ReadAll(reader.get());
    EXPECT_GT(read.size(), 0u);
    ASSERT_LE(read.size(), all.size());
    ExpectSameMessages(read, std::vector<LogMessage>(all.begin(), all.begin() + read.size()));
    std::printf("db cut at %.0f %%: %zu of %zu messages (%s)\n", fraction * 100, read.size(),
                all.size(), reader->recovery()->Summary().c_str());
  }
}

/// A sqlite3 recording whose messages are each a zstd frame, as rosbag2's message compression
/// writes them; `file_mode`: the whole database one zstd stream instead.
std::string CompressedRecording(const std::string& dir, bool file_mode) {
  const std::string name = file_mode ? "plain_f" : "plain_m";
  const std::string plain = Write(dir + "/" + name, LogFormat::kSqlite3, SampleMessages(1.0));
  const std::string bag = dir + (file_mode ? "/per_file" : "/per_message");
  fs::create_directories(bag);
  std::string storage = "per_0.db3";
  if (file_mode) {
    std::ifstream in(plain + "/" + name + "_0.db3", std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::string z(ZSTD_compressBound(bytes.size()), '\0');
    z.resize(ZSTD_compress(z.data(), z.size(), bytes.data(), bytes.size(), 3));
    storage += ".zstd";
    std::ofstream(bag + "/" + storage, std::ios::binary) << z;
  } else {
    detail::SqliteWriter writer(bag + "/" + storage);
    const int64_t imu = writer.AddTopic("/imu", detail::kRos2ImuType, "cdr", "");
    const int64_t points = writer.AddTopic("/points", detail::kRos2CloudType, "cdr", "");
    for (const LogMessage& m : SampleMessages(1.0)) {
      PointCloud2Message cloud;
      if (m.kind == LogMessage::Kind::kScan) {
        cloud = EncodePointCloud2(m.scan, PointTimeConvention::kVelodyne);
      }
      const std::vector<uint8_t> cdr = m.kind == LogMessage::Kind::kImu
                                           ? detail::EncodeCdrImu(m.imu, "imu")
                                           : detail::EncodeCdrPointCloud2(cloud);
      std::vector<uint8_t> z(ZSTD_compressBound(cdr.size()));
      z.resize(ZSTD_compress(z.data(), z.size(), cdr.data(), cdr.size(), 3));
      const bool scan = m.kind == LogMessage::Kind::kScan;
      writer.Write(scan ? points : imu, scan ? m.scan.end_t_ns : m.imu.t_ns, z.data(), z.size());
    }
    writer.Close(5, "");
  }
  WriteText(bag + "/metadata.yaml",
            "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
            "  relative_file_paths: [" +
                storage +
                "]\n  topics_with_message_count: []\n"
                "  compression_format: zstd\n  compression_mode: " +
                std::string(file_mode ? "file" : "message") + "\n");
  return bag;
}

TEST(Rosbag2, Rosbag2sOwnZstdCompressionIsReadPerMessageAndPerFile) {
  const std::string dir = hylo::testing::ScratchDir("rosbag2_compressed");
  const std::string reference = Write(dir + "/ref.bag", LogFormat::kRos1, SampleMessages(1.0));
  for (const bool file_mode : {false, true}) {
    SCOPED_TRACE(file_mode ? "file" : "message");
    const std::string bag = CompressedRecording(dir, file_mode);
    ExpectSameMessages(ReadAll(bag), ReadAll(reference));
    EXPECT_EQ(DescribeRosbag2(bag).compression,
              std::string("zstd (per ") + (file_mode ? "file)" : "message)"));
  }
  // The temporary decompressed database is gone once the reader is.
  for (const auto& e : fs::directory_iterator(fs::temp_directory_path())) {
    EXPECT_EQ(e.path().filename().string().find("hylo_rosbag2_" + std::to_string(::getpid())),
              std::string::npos);
  }
}

TEST(Rosbag2, ALivoxCustomMsgTopicGivesLivoxScans) {
  const std::string dir = hylo::testing::ScratchDir("rosbag2_livox");
  Rosbag2Writer writer(dir + "/livox.mcap", Rosbag2WriterOptions());
  std::vector<detail::LivoxCustomPoint> points(100);
  for (int i = 0; i < 100; ++i) {
    points[i].offset_time_ns = 1000 * i;
    points[i].x = 3.0f + 0.01f * i;
    points[i].line = static_cast<uint8_t>(i % 6);
    points[i].reflectivity = 50;
  }
  for (int k = 0; k < 5; ++k) {
    const int64_t t = testing::kStartNs + k * 100000000LL;
    writer.WriteCdr(
        "/livox/lidar", detail::kLivoxCustomType, t + 99000,
        detail::EncodeCdrLivoxCustom(t, "livox_frame", static_cast<uint64_t>(t), points));
  }
  writer.Close();
  LogReadOptions options;
  options.lidar_topic = "/livox/lidar";
  options.imu_topic = "";
  auto reader = OpenLog(dir + "/livox.mcap", options);
  EXPECT_EQ(reader->time_convention(), PointTimeConvention::kLivox);
  const std::vector<LogMessage> scans = ReadAll(reader.get());
  ASSERT_EQ(scans.size(), 5u);
  EXPECT_EQ(scans[2].scan.points.size(), 100u);
  EXPECT_EQ(scans[2].scan.t_ns, testing::kStartNs + 200000000LL);
  EXPECT_NEAR(scans[2].scan.end_t_ns - scans[2].scan.t_ns, 99000, 256);
  EXPECT_EQ(scans[2].scan.points[7].ring, 1);
}

TEST(Rosbag2, ConvertingBetweenFormatsKeepsEveryMessage) {
  const std::string dir = hylo::testing::ScratchDir("rosbag2_convert");
  const std::string bag = Write(dir + "/a.bag", LogFormat::kRos1, SampleMessages(2.0));
  const ConvertSummary s = ConvertLog(bag, dir + "/b", LogFormat::kMcapZstd, LogReadOptions());
  EXPECT_EQ(s.scans, 20u);
  EXPECT_EQ(s.layout, PointTimeConvention::kVelodyne);
  ConvertLog(dir + "/b", dir + "/c", LogFormat::kSqlite3, LogReadOptions());
  ConvertLog(dir + "/c", dir + "/d.mcap", LogFormat::kMcapLz4, LogReadOptions());
  ConvertLog(dir + "/d.mcap", dir + "/e.bag", LogFormat::kRos1, LogReadOptions());
  ExpectSameMessages(ReadAll(dir + "/e.bag"), ReadAll(bag));
  // A failure half-way leaves nothing behind.
  LogReadOptions wrong;
  wrong.imu_topic = "/points";
  EXPECT_THROW(ConvertLog(bag, dir + "/f", LogFormat::kMcap, wrong), std::runtime_error);
  EXPECT_FALSE(fs::exists(dir + "/f"));
}

TEST(Rosbag2, BrokenRecordingsAreRefusedInOneLineNamingThem) {
  const std::string dir = hylo::testing::ScratchDir("rosbag2_broken");
  const std::string good = Write(dir + "/good", LogFormat::kMcap, SampleMessages(0.5));
  const auto variant = [&](const std::string& name, const std::string& from,
                           const std::string& to) {
    const std::string bag = dir + "/" + name;
    fs::create_directories(bag);
    fs::copy_file(good + "/good_0.mcap", bag + "/good_0.mcap");
    std::ifstream in(good + "/metadata.yaml");
    std::string yaml{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (!from.empty()) yaml.replace(yaml.find(from), from.size(), to);
    WriteText(bag + "/metadata.yaml", yaml);
    return bag;
  };
  const struct {
    std::string bag;
    std::string expected;
  } cases[] = {
      {variant("missing_file", "good_0.mcap", "good_1.mcap"),
       "storage file 'good_1.mcap' (listed in metadata.yaml) is missing"},
      {variant("unknown_storage", "storage_identifier: mcap", "storage_identifier: rosbag_v2"),
       "storage 'rosbag_v2' is not supported"},
      {variant("lz4", "compression_format: \"\"", "compression_format: lz4"),
       "compression 'lz4' is not supported"},
      {variant("malformed", "version: 5", "version: [5"), "metadata.yaml: malformed YAML"},
      {variant("no_version", "version: 5", "versio: 5"),
       "'rosbag2_bagfile_information.version' is missing"},
  };
  for (const auto& c : cases) {
    const std::string error = ErrorOf(c.bag);
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.bag << ": " << error;
    EXPECT_NE(error.find(c.bag), std::string::npos) << error;
  }
  LogReadOptions imu_on_points;
  imu_on_points.imu_topic = "/points";
  EXPECT_NE(ErrorOf(good, imu_on_points)
                .find("topic '/points' has type sensor_msgs/msg/PointCloud2, expected "
                      "sensor_msgs/msg/Imu"),
            std::string::npos);
  WriteText(dir + "/fake.mcap", "not an mcap file at all");
  EXPECT_NE(ErrorOf(dir + "/fake.mcap").find("not a ROS1 bag"), std::string::npos);
}

}  // namespace
}  // namespace hylo::logs
