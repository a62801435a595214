// MCAP files as hylo writes and reads them: every chunk compression round-trips; messages come
// in log-time order through the summary even when chunks overlap; a file written without a
// summary is read record by record; a recording cut short (the recorder killed: no summary, the
// last chunk cut) is read to its last complete message; corrupt chunks and summaries are
// caught by their CRCs.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "hylo/logs/rosbag2_reader.h"
#include "hylo/logs/rosbag2_writer.h"
#include "log_samples.h"
#include "mcap_format.h"
#include "mcap_writer.h"
#include "storage_source.h"
#include "test_data.h"

namespace hylo::logs {
namespace {

using testing::ExpectSameMessages;
using testing::ReadAll;
using testing::SampleMessages;
using testing::WriteMessages;

std::vector<char> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void WriteBytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// Top-level records of an MCAP file: offset and opcode.
std::vector<std::pair<std::size_t, uint8_t>> Records(const std::vector<char>& bytes) {
  std::vector<std::pair<std::size_t, uint8_t>> records;
  for (std::size_t at = 8; at + 9 <= bytes.size() - 8;) {
    const uint8_t op = static_cast<uint8_t>(bytes[at]);
    records.push_back({at, op});
    at += 9 + detail::LoadLe(reinterpret_cast<const uint8_t*>(&bytes[at + 1]), 8);
    if (op == detail::kMcapFooter) break;
  }
  return records;
}

std::string WriteSample(const std::string& path, const std::string& compression,
                        const std::vector<LogMessage>& messages) {
  Rosbag2WriterOptions options;
  options.mcap_compression = compression;
  options.mcap_chunk_bytes = 16 * 1024;  // many chunks
  Rosbag2Writer writer(path, options);
  WriteMessages(messages, &writer);
  writer.Close();
  return path;
}

class McapCompression : public ::testing::TestWithParam<std::string> {};

TEST_P(McapCompression, RoundTripsEveryMessageThroughTheSummary) {
  const std::string dir = hylo::testing::ScratchDir("mcap_round_trip");
  const std::vector<LogMessage> written = SampleMessages(3.0);
  const std::string path = WriteSample(dir + "/a.mcap", GetParam(), written);
  auto reader = OpenLog(path, LogReadOptions());
  EXPECT_EQ(reader->recovery(), nullptr);
  EXPECT_EQ(reader->time_convention(), PointTimeConvention::kVelodyne);
  // The reference: the same messages through a ROS1 bag (float32 time offsets round the same).
  auto bag = CreateLogWriter(dir + "/a.bag", LogFormat::kRos1);
  WriteMessages(written, bag.get());
  bag->Close();
  ExpectSameMessages(ReadAll(reader.get()), ReadAll(dir + "/a.bag"));
  const Rosbag2Description d = DescribeRosbag2(path);
  EXPECT_EQ(d.compression, GetParam().empty() ? "none" : GetParam());
  EXPECT_EQ(d.message_count, written.size());
  EXPECT_GT(d.topics.at(1).point_fields.size(), 0u);  // /points, after /imu
  EXPECT_EQ(d.topics.at(1).detected_convention, PointTimeConvention::kVelodyne);
}

INSTANTIATE_TEST_SUITE_P(Codecs, McapCompression, ::testing::Values("", "zstd", "lz4"),
                         [](const auto& info) {
                           return info.param.empty() ? std::string("stored") : info.param;
                         });

/// Messages on one channel at the given log times, in this order, in chunks of ~`chunk` bytes.
std::string WriteTimes(const std::string& path, const std::vector<uint64_t>& times,
                       uint64_t chunk) {
  detail::McapWriterOptions options;
  options.chunk_bytes = chunk;
  detail::McapWriter writer(path, options);
  const uint16_t schema = writer.AddSchema("std_msgs/msg/UInt64", "ros2msg", "uint64 data\n");
  const uint16_t channel = writer.AddChannel(schema, "/t", "cdr", {});
  for (const uint64_t t : times) {
    const std::vector<uint8_t> data(64, static_cast<uint8_t>(t));
    writer.WriteMessage(channel, t, data.data(), data.size());
  }
  writer.Close();
  return path;
}

std::vector<int64_t> LogTimes(const std::string& path) {
  auto source = detail::OpenMcapSource(path);
  std::vector<int64_t> times;
  detail::StorageMessage m;
  while (source->Next(&m)) times.push_back(m.log_time_ns);
  return times;
}

TEST(Mcap, OverlappingChunksAreMergedInLogTimeOrder) {
  const std::string dir = hylo::testing::ScratchDir("mcap_overlap");
  // Two interleaved runs (a recorder flushing two queues): chunks overlap in time.
  std::vector<uint64_t> times;
  for (uint64_t t = 0; t < 100; t += 2) times.push_back(1000 + t);
  for (uint64_t t = 1; t < 100; t += 2) times.push_back(1000 + t);
  times.push_back(1000);  // a tie with the first message: after it (file order)
  const std::string path = WriteTimes(dir + "/o.mcap", times, 512);
  const std::vector<int64_t> read = LogTimes(path);
  ASSERT_EQ(read.size(), times.size());
  EXPECT_TRUE(std::is_sorted(read.begin(), read.end()));
}

TEST(Mcap, AFileWithoutSummaryIsReadRecordByRecordAndIsNotDamaged) {
  const std::string dir = hylo::testing::ScratchDir("mcap_no_summary");
  const std::vector<LogMessage> written = SampleMessages(1.0);
  std::vector<char> bytes = ReadBytes(WriteSample(dir + "/full.mcap", "zstd", written));
  // Keep the data section (through Data End), then a Footer saying "no summary" and the magic.
  std::size_t data_end = 0;
  for (const auto& [at, op] : Records(bytes)) {
    if (op == detail::kMcapDataEnd) data_end = at + 9 + 4;
  }
  ASSERT_GT(data_end, 0u);
  bytes.resize(data_end);
  const char footer[] = {2, 20, 0, 0, 0, 0, 0, 0, 0};
  bytes.insert(bytes.end(), footer, footer + 9);
  bytes.insert(bytes.end(), 20, 0);
  bytes.insert(bytes.end(), detail::kMcapMagic, detail::kMcapMagic + 8);
  WriteBytes(dir + "/bare.mcap", bytes);
  auto reader = OpenLog(dir + "/bare.mcap", LogReadOptions());
  EXPECT_EQ(reader->recovery(), nullptr);
  ExpectSameMessages(ReadAll(reader.get()), ReadAll(dir + "/full.mcap"));
}

class McapCut : public ::testing::TestWithParam<std::string> {};

TEST_P(McapCut, ARecordingCutShortIsReadToItsLastCompleteMessage) {
  const std::string dir = hylo::testing::ScratchDir("mcap_cut");
  const std::vector<LogMessage> written = SampleMessages(3.0);
  const std::vector<char> whole = ReadBytes(WriteSample(dir + "/whole.mcap", GetParam(), written));
  const std::vector<LogMessage> all = ReadAll(dir + "/whole.mcap");
  std::size_t previous = 0;
  for (const double fraction : {0.05, 0.3, 0.61, 0.9, 0.999}) {
    SCOPED_TRACE(fraction);
    std::vector<char> cut = whole;
    cut.resize(static_cast<std::size_t>(whole.size() * fraction));
    const std::string path = dir + "/cut.mcap";
    WriteBytes(path, cut);
    std::unique_ptr<LogReader> reader;
    try {
      reader = OpenLog(path, LogReadOptions());
    } catch (const std::runtime_error& e) {
      // Cut inside the first compressed block: not even the channels can be read. Said so in
      // one line, as for a ROS1 bag cut before its first scan.
      EXPECT_LT(fraction, 0.1);
      EXPECT_NE(std::string(e.what()).find("cut.mcap': no topic '/points'"), std::string::npos)
          << e.what();
      continue;
    }
    ASSERT_NE(reader->recovery(), nullptr);
    const std::vector<LogMessage> read = ReadAll(reader.get());
    const LogRecovery& r = *reader->recovery();
    EXPECT_NE(r.damage.find("no footer (recording interrupted?)"), std::string::npos) << r.damage;
    EXPECT_EQ(r.Summary().find('\n'), std::string::npos);
    EXPECT_LE(r.unreadable_bytes, cut.size());
    EXPECT_GE(read.size(), previous);  // more bytes, never fewer messages
    ASSERT_LE(read.size(), all.size());
    ExpectSameMessages(read, std::vector<LogMessage>(all.begin(), all.begin() + read.size()));
    previous = read.size();
  }
  EXPECT_GT(previous, all.size() * 9 / 10);
}

INSTANTIATE_TEST_SUITE_P(Codecs, McapCut, ::testing::Values("", "zstd", "lz4"),
                         [](const auto& info) {
                           return info.param.empty() ? std::string("stored") : info.param;
                         });

TEST(Mcap, InsideAStoredChunkThatIsCutEveryWholeMessageIsKept) {
  const std::string dir = hylo::testing::ScratchDir("mcap_cut_stored");
  const std::vector<LogMessage> written = SampleMessages(1.0);
  Rosbag2WriterOptions options;
  options.mcap_chunk_bytes = 1 << 30;  // one chunk: everything is inside the cut one
  Rosbag2Writer writer(dir + "/one.mcap", options);
  WriteMessages(written, &writer);
  writer.Close();
  std::vector<char> bytes = ReadBytes(dir + "/one.mcap");
  bytes.resize(bytes.size() / 2);
  WriteBytes(dir + "/half.mcap", bytes);
  auto reader = OpenLog(dir + "/half.mcap", LogReadOptions());
  const std::size_t n = ReadAll(reader.get()).size();
  EXPECT_GT(n, written.size() / 3);
  EXPECT_LT(n, written.size() * 2 / 3);
  EXPECT_NE(reader->recovery()->stop_reason.find("the last chunk is cut"), std::string::npos);
}

TEST(Crc32, MatchesTheTablesAtEveryLengthAndAlignment) {
  // The check value of the CRC-32 catalogue, then random data: lengths around every fold
  // boundary, every alignment, and a CRC continued across two calls.
  const std::string check = "123456789";
  EXPECT_EQ(detail::Crc32(reinterpret_cast<const uint8_t*>(check.data()), check.size()),
            0xCBF43926u);
  std::vector<uint8_t> data(70000);
  uint32_t state = 12345;
  for (uint8_t& b : data) {
    state = state * 1664525u + 1013904223u;
    b = static_cast<uint8_t>(state >> 24);
  }
  for (std::size_t n = 0; n < 600; ++n) {
    for (std::size_t offset : {0, 1, 3, 8, 15}) {
      ASSERT_EQ(detail::Crc32(data.data() + offset, n), detail::Crc32Tables(data.data() + offset, n))
          << n << " bytes at offset " << offset;
    }
  }
  for (std::size_t n : {4095, 4096, 65536, 69999}) {
    EXPECT_EQ(detail::Crc32(data.data(), n), detail::Crc32Tables(data.data(), n)) << n;
    const uint32_t first = detail::Crc32(data.data(), n / 3);
    EXPECT_EQ(detail::Crc32(data.data() + n / 3, n - n / 3, first),
              detail::Crc32Tables(data.data(), n))
        << n;
  }
}

TEST(Mcap, ACorruptChunkOrSummaryIsCaughtByItsCrc) {
  const std::string dir = hylo::testing::ScratchDir("mcap_crc");
  const std::vector<LogMessage> written = SampleMessages(1.0);
  const std::vector<char> whole = ReadBytes(WriteSample(dir + "/a.mcap", "", written));
  const auto records = Records(whole);
  // A byte of a stored chunk's records flipped: the summary sends the reader there, the CRC
  // refuses it, and the error names the file.
  std::vector<char> bytes = whole;
  std::size_t chunk_at = 0;
  for (const auto& [at, op] : records) {
    if (op == detail::kMcapChunk && chunk_at == 0) chunk_at = at;
  }
  bytes[chunk_at + 200] ^= 0x55;
  WriteBytes(dir + "/chunk.mcap", bytes);
  try {
    ReadAll(dir + "/chunk.mcap");
    FAIL() << "a corrupt chunk was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("chunk.mcap"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("CRC"), std::string::npos) << e.what();
  }
  // A byte of the summary flipped: the summary is not trusted; the file is read record by
  // record, whole, and said to be damaged.
  bytes = whole;
  std::size_t summary_at = 0;
  for (const auto& [at, op] : records) {
    if (op == detail::kMcapStatistics) summary_at = at;
  }
  bytes[summary_at + 12] ^= 0x55;
  WriteBytes(dir + "/summary.mcap", bytes);
  auto reader = OpenLog(dir + "/summary.mcap", LogReadOptions());
  ASSERT_NE(reader->recovery(), nullptr);
  EXPECT_NE(reader->recovery()->damage.find("CRC"), std::string::npos);
  EXPECT_EQ(ReadAll(reader.get()).size(), written.size());
}

}  // namespace
}  // namespace hylo::logs
