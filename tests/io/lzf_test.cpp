#include "hylo/io/lzf.h"

#include <gtest/gtest.h>

#include <random>

namespace hylo::io {
namespace {

std::vector<uint8_t> RoundTrip(const std::vector<uint8_t>& data, std::size_t* packed_size) {
  const std::vector<uint8_t> packed = LzfCompress(data.data(), data.size());
  *packed_size = packed.size();
  std::vector<uint8_t> out;
  std::string why;
  EXPECT_TRUE(LzfDecompress(packed.data(), packed.size(), data.size(), &out, &why)) << why;
  return out;
}

TEST(Lzf, DecodesAHandWrittenStreamWithOverlappingReference) {
  // Literal run "abc" (ctrl 2), then a reference of 6 bytes (length field 4) at distance 3
  // (offset field 2): the copy overlaps what it writes, giving "abcabcabc".
  const std::vector<uint8_t> stream = {2, 'a', 'b', 'c', (4 << 5) | 0, 2};
  std::vector<uint8_t> out;
  std::string why;
  ASSERT_TRUE(LzfDecompress(stream.data(), stream.size(), 9, &out, &why)) << why;
  EXPECT_EQ(std::string(out.begin(), out.end()), "abcabcabc");
}

TEST(Lzf, DecodesALongReferenceWithExtensionByte) {
  // Length field 7 + extension 10 = 17 -> 19 bytes copied from distance 1 (a run of 'x').
  const std::vector<uint8_t> stream = {0, 'x', (7 << 5) | 0, 10, 0};
  std::vector<uint8_t> out;
  std::string why;
  ASSERT_TRUE(LzfDecompress(stream.data(), stream.size(), 20, &out, &why)) << why;
  EXPECT_EQ(std::string(out.begin(), out.end()), std::string(20, 'x'));
}

TEST(Lzf, RoundTripsEdgeSizesAndRandomData) {
  std::mt19937 rng(7);
  for (std::size_t size : {0u, 1u, 2u, 3u, 31u, 32u, 33u, 64u, 1000u, 100000u}) {
    std::vector<uint8_t> data(size);
    for (auto& b : data) b = static_cast<uint8_t>(rng());
    std::size_t packed = 0;
    EXPECT_EQ(RoundTrip(data, &packed), data) << "size " << size;
    // Incompressible: growth bounded by one control byte per 32-byte literal run.
    EXPECT_LE(packed, size + (size + 31) / 32) << "size " << size;
  }
}

TEST(Lzf, CompressesRepetitiveDataAndLongRuns) {
  std::vector<uint8_t> data;
  for (int i = 0; i < 50000; ++i) data.push_back(static_cast<uint8_t>("substation"[i % 10]));
  data.insert(data.end(), 70000, 0);  // a run far longer than one reference (264 bytes)
  std::size_t packed = 0;
  EXPECT_EQ(RoundTrip(data, &packed), data);
  EXPECT_LT(packed, data.size() / 50);
}

TEST(Lzf, RoundTripsFloatLikeData) {
  // Slowly varying float32 values, as in a field-major PCD block.
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.f, 0.01f);
  std::vector<uint8_t> data;
  for (int i = 0; i < 20000; ++i) {
    const float v = 100.f + 0.001f * static_cast<float>(i) + noise(rng);
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    data.insert(data.end(), p, p + 4);
  }
  std::size_t packed = 0;
  EXPECT_EQ(RoundTrip(data, &packed), data);
}

TEST(Lzf, RejectsCorruptStreams) {
  std::vector<uint8_t> out;
  std::string why;
  const std::vector<uint8_t> cut_literal = {5, 'a', 'b'};
  EXPECT_FALSE(LzfDecompress(cut_literal.data(), cut_literal.size(), 6, &out, &why));
  EXPECT_NE(why.find("literal"), std::string::npos) << why;
  const std::vector<uint8_t> before_start = {0, 'a', (1 << 5) | 0, 5};  // distance 6 > 1 byte
  EXPECT_FALSE(LzfDecompress(before_start.data(), before_start.size(), 4, &out, &why));
  EXPECT_NE(why.find("before the start"), std::string::npos) << why;
  const std::vector<uint8_t> cut_reference = {0, 'a', (7 << 5)};
  EXPECT_FALSE(LzfDecompress(cut_reference.data(), cut_reference.size(), 10, &out, &why));
  const std::vector<uint8_t> good = {2, 'a', 'b', 'c'};
  EXPECT_FALSE(LzfDecompress(good.data(), good.size(), 4, &out, &why));  // announced too long
  EXPECT_FALSE(LzfDecompress(good.data(), good.size(), 2, &out, &why));  // announced too short
}

}  // namespace
}  // namespace hylo::io
