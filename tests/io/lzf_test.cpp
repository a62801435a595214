// LZF, the compression of PCD `binary_compressed`, comes from liblzf. Checked here: the
// contract the PCD reader relies on (corrupt or cut streams give 0 and EINVAL/E2BIG, every
// buffer exactly sized so that a sanitizer or valgrind run sees any access out of bounds),
// and the reader's errors on corrupt blocks, naming the file.
#include <gtest/gtest.h>
#include <lzf.h>

#include <cerrno>
#include <random>

#include "cloud_test_util.h"
#include "hylo/io/cloud_io.h"
#include "test_data.h"

namespace hylo::io {
namespace {

struct Decoded {
  unsigned int size = 0;  ///< lzf_decompress's return value
  int error = 0;          ///< errno after it
};

// Decodes from a heap copy of exactly `stream.size()` bytes into exactly `capacity` bytes.
Decoded Decode(const std::vector<uint8_t>& stream, std::size_t capacity) {
  const std::vector<uint8_t> in(stream);
  std::vector<uint8_t> out(capacity);
  errno = 0;
  Decoded d;
  d.size = lzf_decompress(in.data(), static_cast<unsigned int>(in.size()), out.data(),
                          static_cast<unsigned int>(out.size()));
  d.error = errno;
  return d;
}

std::vector<uint8_t> Compress(const std::vector<uint8_t>& raw) {
  std::vector<uint8_t> out(raw.size() + raw.size() / 32 + 64);
  out.resize(lzf_compress(raw.data(), static_cast<unsigned int>(raw.size()), out.data(),
                          static_cast<unsigned int>(out.size())));
  return out;
}

TEST(LibLzf, CorruptStreamsGiveZeroAndTheReasonInErrno) {
  struct Case {
    std::vector<uint8_t> stream;
    std::size_t capacity;
    int error;
  };
  const Case cases[] = {
      {{5, 'a', 'b'}, 6, EINVAL},                  // literal run past the end of the input
      {{0, 'a', (1 << 5) | 0, 5}, 4, EINVAL},      // reference 6 bytes back after 1 byte
      {{0, 'a', (7 << 5)}, 10, EINVAL},            // long reference cut before its length byte
      {{0, 'a', (7 << 5), 3}, 10, EINVAL},         // ... and before its offset byte
      {{2, 'a', 'b', 'c'}, 2, E2BIG},              // longer than announced
      {{0, 'x', (7 << 5) | 0, 10, 0}, 19, E2BIG},  // a run of 20 into 19 bytes
  };
  for (const Case& c : cases) {
    const Decoded d = Decode(c.stream, c.capacity);
    EXPECT_EQ(d.size, 0u);
    EXPECT_EQ(d.error, c.error);
  }
  // Shorter than announced is no error to liblzf: the caller compares the size.
  EXPECT_EQ(Decode({2, 'a', 'b', 'c'}, 4).size, 3u);
}

TEST(LibLzf, EveryCutOfARealStreamIsCaught) {
  std::mt19937 rng(11);
  std::normal_distribution<float> noise(0.f, 0.01f);
  std::vector<uint8_t> raw;
  for (int i = 0; i < 3000; ++i) {  // slowly varying floats, as in a field-major PCD block
    const float v = 100.f + 0.001f * static_cast<float>(i % 500) + noise(rng);
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    raw.insert(raw.end(), p, p + 4);
  }
  const std::vector<uint8_t> stream = Compress(raw);
  ASSERT_FALSE(stream.empty());
  ASSERT_LT(stream.size(), raw.size());
  EXPECT_EQ(Decode(stream, raw.size()).size, raw.size());
  for (std::size_t cut = 1; cut < stream.size(); ++cut) {
    const Decoded d = Decode({stream.begin(), stream.begin() + cut}, raw.size());
    EXPECT_LT(d.size, raw.size()) << "cut at " << cut;
    if (d.size == 0) {
      EXPECT_EQ(d.error, EINVAL) << "cut at " << cut;
    }
  }
}

TEST(LibLzf, RandomBytesNeverOverrunTheBuffers) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<uint8_t> garbage(1 + rng() % 64);
    for (auto& b : garbage) b = static_cast<uint8_t>(rng());
    const std::size_t capacity = 1 + rng() % 256;
    EXPECT_LE(Decode(garbage, capacity).size, capacity);
  }
}

// A PCD of three points (1, 1, 1) whose block is written by hand: a 4-byte literal, then one
// reference 4 bytes back for 32 bytes, overlapping what it writes.
std::vector<uint8_t> HandWrittenBlock(uint32_t compressed_size, uint32_t raw_size) {
  const std::vector<uint8_t> stream = {3, 0x00, 0x00, 0x80, 0x3f, (7 << 5) | 0, 23, 3};
  std::vector<uint8_t> block;
  testing::Append(&block, compressed_size);
  testing::Append(&block, raw_size);
  block.insert(block.end(), stream.begin(), stream.end());
  return block;
}

const char kThreePointHeader[] =
    "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 1\n"
    "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA binary_compressed\n";

TEST(PcdLzf, ReadsAHandWrittenBlockWithAnOverlappingReference) {
  const std::string path = hylo::testing::ScratchDir("pcd_lzf") + "/hand.pcd";
  testing::WriteRaw(path, kThreePointHeader, HandWrittenBlock(8, 36));
  const CloudFile cloud = ReadCloud(path);
  ASSERT_EQ(cloud.positions.size(), 3u);
  for (const Eigen::Vector3d& p : cloud.positions) EXPECT_EQ(p, Eigen::Vector3d(1, 1, 1));
}

void ExpectCorrupt(const std::string& path, const std::string& reason) {
  testing::ExpectReadError(path, "corrupt compressed data: " + reason);
}

TEST(PcdLzf, CorruptBlocksAreErrorsNamingTheFileAndReason) {
  const std::string dir = hylo::testing::ScratchDir("pcd_lzf");
  // The stream announced shorter than written: cut inside the reference.
  testing::WriteRaw(dir + "/cut.pcd", kThreePointHeader, HandWrittenBlock(6, 36));
  ExpectCorrupt(dir + "/cut.pcd", "LZF stream cut short");
  // Only the literal: 4 of the 36 bytes.
  testing::WriteRaw(dir + "/short.pcd", kThreePointHeader, HandWrittenBlock(5, 36));
  ExpectCorrupt(dir + "/short.pcd", "LZF data expands to 4 of the 36 bytes");
  // No stream at all for three points.
  testing::WriteRaw(dir + "/empty.pcd", kThreePointHeader, HandWrittenBlock(0, 36));
  ExpectCorrupt(dir + "/empty.pcd", "LZF data expands to 0 of the 36 bytes");
  // The reference reaching back before the start of the output.
  std::vector<uint8_t> before_start = HandWrittenBlock(8, 36);
  before_start.back() = 9;
  testing::WriteRaw(dir + "/before.pcd", kThreePointHeader, before_start);
  ExpectCorrupt(dir + "/before.pcd", "LZF stream cut short or referring before its start");
  // A longer run than the points need (the block's sizes agree with the header).
  std::vector<uint8_t> too_long = HandWrittenBlock(8, 36);
  too_long[8 + 6] = 24;
  testing::WriteRaw(dir + "/long.pcd", kThreePointHeader, too_long);
  ExpectCorrupt(dir + "/long.pcd", "LZF data expands past the 36 bytes");
}

}  // namespace
}  // namespace hylo::io
