// Bags whose recording was killed or that were cut short: read up to the last complete
// message. Which messages are complete is found independently of the reader, by locating each
// message's own bytes in the file (every message written here is unique): an Imu message ends
// 72 bytes (the acceleration covariance) after its acceleration, a PointCloud2 one byte
// (is_dense) after its point data.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/logs/bag_reader.h"
#include "hylo/logs/bag_writer.h"
#include "test_data.h"

namespace hylo::logs {
namespace {

constexpr int64_t kStartNs = 1700000000000000000;
constexpr int64_t kImuPeriodNs = 5000000;     // 200 Hz
constexpr int64_t kScanPeriodNs = 100000000;  // 10 Hz
constexpr char kImuTopic[] = "/imu";
constexpr char kScanTopic[] = "/points";

struct Written {
  int64_t t_ns = 0;
  bool scan = false;
  std::vector<char> tail;  // bytes that end the message (see EndOffset)
  std::size_t after_tail = 0;
};

std::vector<char> Bytes(const void* p, std::size_t n) {
  const char* c = static_cast<const char*>(p);
  return std::vector<char>(c, c + n);
}

/// Writes `seconds` of 200 Hz IMU (accelerations unique per sample) and 10 Hz scans of random
/// points in receive order, as a recorder would; returns what was written, in order.
/// `at_half` (may be empty) runs once half-way, with the writer still open.
std::vector<Written> WriteRecording(BagWriter* writer, double seconds, int points,
                                    const std::function<void()>& at_half = {}) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-40.f, 40.f);
  std::vector<Written> written;
  bool halfway_done = false;
  const int64_t end_ns = kStartNs + static_cast<int64_t>(seconds * 1e9);
  for (int64_t t = kStartNs; t < end_ns; t += kImuPeriodNs) {
    ImuSample imu;
    imu.t_ns = t;
    imu.accel_imu = {0.001 * written.size(), 0.1 + 1e-6 * (t - kStartNs) / kImuPeriodNs, 9.81};
    imu.gyro_imu = {0.01, -0.02, 0.03};
    writer->WriteImu(kImuTopic, imu, "imu");
    written.push_back({t, false, Bytes(imu.accel_imu.data(), 24), 72});
    if ((t - kStartNs) % kScanPeriodNs != 0) continue;
    LidarScan scan;
    scan.t_ns = t;
    for (int i = 0; i < points; ++i) {
      ScanPoint p;
      p.position_lidar = {coord(rng), coord(rng), coord(rng)};
      p.offset_ns = i * (kScanPeriodNs / points);
      scan.points.push_back(p);
    }
    scan.end_t_ns = t + scan.points.back().offset_ns;
    writer->WriteScan(kScanTopic, scan, PointTimeConvention::kVelodyne, "lidar");
    const std::vector<uint8_t> data = EncodePointCloud2(scan, PointTimeConvention::kVelodyne).data;
    written.push_back({scan.end_t_ns, true, Bytes(data.data() + data.size() - 32, 32), 1});
    if (at_half && t >= kStartNs + (end_ns - kStartNs) / 2 && !halfway_done) {
      at_half();
      halfway_done = true;
    }
  }
  return written;
}

std::vector<char> ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Where each written message ends in `file` (npos when its bytes are not all there).
std::vector<std::size_t> EndOffsets(const std::vector<char>& file,
                                    const std::vector<Written>& written) {
  std::vector<std::size_t> ends;
  for (const Written& w : written) {
    const auto it = std::search(file.begin(), file.end(), w.tail.begin(), w.tail.end());
    std::size_t end = std::string::npos;
    if (it != file.end()) {
      end = static_cast<std::size_t>(it - file.begin()) + w.tail.size() + w.after_tail;
      if (end > file.size()) end = std::string::npos;
    }
    ends.push_back(end);
  }
  return ends;
}

struct ReadBack {
  std::vector<int64_t> stamps;  // scans: end stamps, IMU: stamps, in delivery order
  std::vector<bool> is_scan;
  LogRecovery recovery;
  bool recovered = false;
};

ReadBack ReadAll(const std::string& path) {
  LogReadOptions options;
  options.lidar_topic = kScanTopic;
  options.imu_topic = kImuTopic;
  auto reader = OpenBag(path, options);
  ReadBack out;
  LogMessage m;
  while (reader->Next(&m)) {
    const bool scan = m.kind == LogMessage::Kind::kScan;
    out.is_scan.push_back(scan);
    out.stamps.push_back(scan ? m.scan.end_t_ns : m.imu.t_ns);
  }
  if (reader->recovery() != nullptr) {
    out.recovered = true;
    out.recovery = *reader->recovery();
  }
  return out;
}

/// IMU stamps are exact; a scan's end comes back through the Velodyne layout's float32 time
/// offsets, within a microsecond.
void ExpectStamp(const ReadBack& got, const std::vector<Written>& written, std::size_t i) {
  if (written[i].scan) {
    EXPECT_NEAR(got.stamps[i], written[i].t_ns, 1000) << i;
  } else {
    EXPECT_EQ(got.stamps[i], written[i].t_ns) << i;
  }
}

/// The messages fully inside the first `cut` bytes, in order, are exactly what was read.
void ExpectPrefix(const ReadBack& got, const std::vector<Written>& written,
                  const std::vector<std::size_t>& ends, std::size_t cut) {
  std::size_t complete = 0;
  while (complete < written.size() && ends[complete] != std::string::npos &&
         ends[complete] <= cut) {
    ++complete;
  }
  for (std::size_t i = complete; i < written.size(); ++i) {  // none completes after a gap
    EXPECT_TRUE(ends[i] == std::string::npos || ends[i] > cut) << "message " << i;
  }
  ASSERT_EQ(got.stamps.size(), complete) << "cut at byte " << cut;
  for (std::size_t i = 0; i < complete; ++i) {
    ASSERT_EQ(got.is_scan[i], written[i].scan) << i;
    ExpectStamp(got, written, i);
  }
}

TEST(BagRecovery, EveryMessageBeforeACutIsRead) {
  const std::string dir = testing::ScratchDir("bag_recovery_cut");
  std::vector<Written> written;
  {
    BagWriter writer(dir + "/whole.bag");
    written = WriteRecording(&writer, 4.0, 2000);
    writer.Close();
  }
  const std::vector<char> whole = ReadFile(dir + "/whole.bag");
  const std::vector<std::size_t> ends = EndOffsets(whole, written);
  for (std::size_t e : ends) ASSERT_NE(e, std::string::npos);  // the patterns are in the file
  std::mt19937 rng(2023);
  std::uniform_int_distribution<std::size_t> offset(13, whole.size() - 1);
  for (int k = 0; k < 10; ++k) {
    const std::size_t cut = offset(rng);
    const std::string path = dir + "/cut_" + std::to_string(k) + ".bag";
    std::ofstream(path, std::ios::binary).write(whole.data(), static_cast<std::streamsize>(cut));
    if (cut < ends[1]) {
      // No scan is complete: the only acceptable refusal is a lidar topic not seen yet.
      try {
        ReadAll(path);
      } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("no topic '/points'"), std::string::npos) << e.what();
        continue;
      }
    }
    const ReadBack got = ReadAll(path);
    SCOPED_TRACE("cut at byte " + std::to_string(cut) + " of " + std::to_string(whole.size()));
    ExpectPrefix(got, written, ends, cut);
    ASSERT_TRUE(got.recovered);
    EXPECT_EQ(got.recovery.messages, got.stamps.size());
    EXPECT_EQ(got.recovery.file_bytes, cut);
    if (!got.stamps.empty()) {
      std::size_t last_end = ends[got.stamps.size() - 1];
      EXPECT_LE(got.recovery.unreadable_bytes, cut - last_end);
      EXPECT_NEAR(got.recovery.span_s(), (got.stamps.back() - kStartNs) * 1e-9, 1e-9);
    }
    std::printf("cut at %zu / %zu bytes: %s\n", cut, whole.size(), got.recovery.Summary().c_str());
    // `hylo info` describes the same messages.
    const BagDescription d = DescribeBag(path);
    ASSERT_TRUE(d.recovery.has_value());
    EXPECT_EQ(d.message_count, got.stamps.size());
    EXPECT_EQ(d.recovery->unreadable_bytes, got.recovery.unreadable_bytes);
  }
}

TEST(BagRecovery, AKilledRecordingIsReadUpToItsLastCompleteMessage) {
  const std::string dir = testing::ScratchDir("bag_recovery_killed");
  std::vector<Written> written;
  {
    BagWriter writer(dir + "/live.bag");
    // The copy is what a killed recorder leaves: no index, the last chunk never closed.
    written = WriteRecording(&writer, 3.0, 2000, [&] {
      std::filesystem::copy_file(dir + "/live.bag", dir + "/killed.bag");
    });
  }
  const std::vector<char> killed = ReadFile(dir + "/killed.bag");
  const std::vector<std::size_t> ends = EndOffsets(killed, written);
  const ReadBack got = ReadAll(dir + "/killed.bag");
  ExpectPrefix(got, written, ends, killed.size());
  ASSERT_TRUE(got.recovered);
  EXPECT_NE(got.recovery.damage.find("no index"), std::string::npos) << got.recovery.damage;
  EXPECT_GT(got.stamps.size(), written.size() / 3);  // chunks of the first half reached disk
  std::printf("killed recording: %s\n", got.recovery.Summary().c_str());
}

TEST(BagRecovery, IndexedBagsAreStillReadThroughTheirIndex) {
  const std::string dir = testing::ScratchDir("bag_recovery_whole");
  std::vector<Written> written;
  {
    BagWriter writer(dir + "/whole.bag");
    written = WriteRecording(&writer, 1.0, 500);
  }
  const ReadBack got = ReadAll(dir + "/whole.bag");
  EXPECT_FALSE(got.recovered);
  EXPECT_EQ(got.stamps.size(), written.size());
  EXPECT_FALSE(DescribeBag(dir + "/whole.bag").recovery.has_value());
}

class CompressedBagRecovery : public ::testing::TestWithParam<BagCompression> {};

// Compressed chunks hide where each message lies in the file: what is checked is that what
// comes out is the recording's beginning, all of it when only the index is cut, and the
// messages of the whole chunks before a cut inside the data.
TEST_P(CompressedBagRecovery, ReadsTheMessagesOfEveryReadableChunk) {
  const std::string dir = testing::ScratchDir("bag_recovery_compressed");
  std::vector<Written> written;
  {
    BagWriter writer(dir + "/whole.bag", GetParam());
    written = WriteRecording(&writer, 4.0, 2000);
  }
  const std::vector<char> whole = ReadFile(dir + "/whole.bag");
  std::vector<std::size_t> all_complete(written.size(), 0);
  for (const double keep : {0.999, 0.8, 0.5}) {
    const std::size_t cut = static_cast<std::size_t>(whole.size() * keep);
    const std::string path = dir + "/cut.bag";
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(whole.data(), static_cast<std::streamsize>(cut));
    const ReadBack got = ReadAll(path);
    ASSERT_TRUE(got.recovered);
    ASSERT_LE(got.stamps.size(), written.size());
    for (std::size_t i = 0; i < got.stamps.size(); ++i) {
      ASSERT_EQ(got.is_scan[i], written[i].scan) << i;
      ExpectStamp(got, written, i);
    }
    std::printf("%s, cut at %.1f %%: %s\n", GetParam() == BagCompression::kBz2 ? "bz2" : "lz4",
                100 * keep, got.recovery.Summary().c_str());
    if (keep == 0.999) {
      EXPECT_EQ(got.stamps.size(), written.size()) << "only the index was cut";
    } else {
      EXPECT_GT(got.stamps.size(), 0u);
      EXPECT_LT(got.stamps.size(), written.size());
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Codecs, CompressedBagRecovery,
                         ::testing::Values(BagCompression::kBz2, BagCompression::kLz4),
                         [](const auto& info) {
                           return info.param == BagCompression::kBz2 ? "bz2" : "lz4";
                         });

TEST(BagRecovery, CorruptRecordStopsTheWalkAndKeepsWhatCameBefore) {
  const std::string dir = testing::ScratchDir("bag_recovery_corrupt");
  std::vector<Written> written;
  {
    BagWriter writer(dir + "/whole.bag");
    written = WriteRecording(&writer, 2.0, 1000);
  }
  std::vector<char> bytes = ReadFile(dir + "/whole.bag");
  const std::vector<std::size_t> ends = EndOffsets(bytes, written);
  // Overwrite the length of a record header in the middle with garbage, and cut the index.
  const std::size_t damaged = ends[written.size() / 2];
  std::memset(bytes.data() + damaged, 0xff, 4);
  bytes.resize(bytes.size() - 100);
  const std::string path = dir + "/damaged.bag";
  std::ofstream(path, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  const ReadBack got = ReadAll(path);
  ASSERT_TRUE(got.recovered);
  ExpectPrefix(got, written, ends, damaged);
  EXPECT_FALSE(got.recovery.stop_reason.empty());
  EXPECT_EQ(got.recovery.unreadable_bytes, bytes.size() - damaged);
}

}  // namespace
}  // namespace hylo::logs
