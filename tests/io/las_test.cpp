// LAS written by hylo: quantization on the 0.1 mm grid, bit-identical read-back and
// byte-identical rewrite, attributes, the header a reader expects, and what LAS cannot hold.
// Files of every point format (0-10) built from the specification's offsets read back as built.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "cloud_test_util.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/cloud_stream.h"
#include "las_test_util.h"
#include "test_data.h"

namespace hylo::io {
namespace {

using testing::At;
using testing::ExpectReadError;
using testing::FileBytes;
using testing::ParseRawHeader;
using testing::RawLasHeader;

std::string Dir() {
  static const std::string dir = hylo::testing::ScratchDir("las");
  return dir;
}

// A cloud LAS can hold: integer intensities, labels 0-255, normals; around `center`.
CloudFile LasCloud(std::size_t n, const Eigen::Vector3d& center, double half_extent_m,
                   unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(-half_extent_m, half_extent_m);
  std::uniform_int_distribution<int> byte(0, 255), word(0, 65535);
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  CloudFile cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.positions.push_back(center + Eigen::Vector3d(coord(rng), coord(rng), coord(rng)));
    cloud.intensity.push_back(static_cast<float>(word(rng)));
    cloud.labels.push_back(byte(rng));
    cloud.normals.push_back(Eigen::Vector3f(unit(rng), unit(rng), unit(rng)).normalized());
  }
  return cloud;
}

struct Place {
  const char* name;
  Eigen::Vector3d center;
  double half_extent_m;
};
void PrintTo(const Place& p, std::ostream* os) { *os << p.name; }

class LasRoundTrip : public ::testing::TestWithParam<Place> {};

TEST_P(LasRoundTrip, QuantizedToATenthOfAMillimetreThenBitIdentical) {
  const std::string path = Dir() + "/" + GetParam().name + ".las";
  const CloudFile cloud = LasCloud(3000, GetParam().center, GetParam().half_extent_m, 3);
  WriteCloud(path, cloud);
  const std::vector<uint8_t> bytes = FileBytes(path);
  const RawLasHeader h = ParseRawHeader(bytes);
  EXPECT_EQ(h.scale, Eigen::Vector3d::Constant(1e-4));
  const CloudFile read = ReadCloud(path);
  ASSERT_EQ(read.positions.size(), cloud.positions.size());
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    // Exactly the record integer times scale plus offset, and within half a step of the input.
    ASSERT_EQ(read.positions[i], testing::RawPosition(bytes, h, i)) << i;
    ASSERT_LE((read.positions[i] - cloud.positions[i]).cwiseAbs().maxCoeff(), 0.5e-4 + 1e-9) << i;
  }
  EXPECT_EQ(read.intensity, cloud.intensity);
  EXPECT_EQ(read.labels, cloud.labels);
  EXPECT_EQ(read.normals, cloud.normals);
  // write(read(write(x))) is the same file, and reads back to the same cloud.
  const std::string again = Dir() + "/" + GetParam().name + "_again.las";
  WriteCloud(again, read);
  EXPECT_EQ(FileBytes(again), bytes);
  EXPECT_EQ(ReadCloud(again).positions, read.positions);
}

INSTANTIATE_TEST_SUITE_P(
    Places, LasRoundTrip,
    ::testing::Values(Place{"local", Eigen::Vector3d(1.0, -2.0, 0.5), 60.0},
                      Place{"utm", Eigen::Vector3d(512345.678, 5412345.678, 312.5), 400.0},
                      Place{"negative", Eigen::Vector3d(-35000.0, -1000.0, -999.99995), 20.0},
                      Place{"on_a_km_line", Eigen::Vector3d(600000.0, 5200000.0, 0.0), 0.001},
                      Place{"wide", Eigen::Vector3d(500000.0, 5000000.0, 0.0), 100000.0}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(Las, HeaderIsLas14Format6WithCountsBoundsAndTheNormalsDescribed) {
  const std::string path = Dir() + "/header.las";
  CloudFile cloud = LasCloud(10, Eigen::Vector3d(700000.0, 5300000.0, 100.0), 5.0, 1);
  WriteCloud(path, cloud);
  std::vector<uint8_t> b = FileBytes(path);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "LASF");
  EXPECT_EQ(b[24], 1);
  EXPECT_EQ(b[25], 4);
  EXPECT_EQ(At<uint16_t>(b, 6) & 0x10, 0x10);  // formats 6-10 declare WKT
  EXPECT_EQ(At<uint16_t>(b, 94), 375);
  EXPECT_EQ(At<uint32_t>(b, 100), 1u);  // the Extra Bytes VLR
  EXPECT_EQ(At<uint32_t>(b, 96), 375u + 54 + 3 * 192);
  EXPECT_EQ(b[104], 6);
  EXPECT_EQ(At<uint16_t>(b, 105), 30 + 12);
  EXPECT_EQ(At<uint32_t>(b, 107), 0u);  // legacy count: 0 for format 6
  EXPECT_EQ(At<uint64_t>(b, 247), 10u);
  EXPECT_EQ(At<uint64_t>(b, 255), 10u);  // all first returns
  EXPECT_EQ(b.size(), 375u + 54 + 3 * 192 + 10 * 42);
  const CloudFile read = ReadCloud(path);
  Eigen::Vector3d lo = read.positions[0], hi = read.positions[0];
  for (const Eigen::Vector3d& p : read.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(At<double>(b, 179 + 16 * k), hi[k]);
    EXPECT_EQ(At<double>(b, 187 + 16 * k), lo[k]);
  }
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&b[375 + 54 + 4])), "NormalX");
  const CloudFileInfo info = ReadCloudInfo(path);
  EXPECT_EQ(info.format, "las");
  EXPECT_EQ(info.encoding, "LAS 1.4 point format 6");
  EXPECT_EQ(info.points, 10u);
  // Without attributes: 30-byte records, no VLR, intensity and class 0.
  WriteCloud(path, CloudFile{cloud.positions, {}, {}, {}, 0});
  b = FileBytes(path);
  EXPECT_EQ(At<uint16_t>(b, 105), 30);
  EXPECT_EQ(At<uint32_t>(b, 96), 375u);
  EXPECT_EQ(ReadCloud(path).labels, std::vector<int32_t>(10, 0));
  EXPECT_TRUE(ReadCloud(path).normals.empty());
}

TEST(Las, EmptyCloudAndFractionalIntensity) {
  WriteCloud(Dir() + "/empty.las", CloudFile());
  EXPECT_TRUE(ReadCloud(Dir() + "/empty.las").positions.empty());
  EXPECT_EQ(ReadCloudInfo(Dir() + "/empty.las").points, 0u);
  CloudFile cloud;
  cloud.positions = {{1, 2, 3}, {4, 5, 6}};
  cloud.intensity = {0.4f, 17.5f};  // LAS intensity is an integer: rounded
  WriteCloud(Dir() + "/fraction.las", cloud);
  EXPECT_EQ(ReadCloud(Dir() + "/fraction.las").intensity, (std::vector<float>{0.f, 18.f}));
}

TEST(Las, WhatLasCannotHoldIsRefusedNamingThePoint) {
  const auto expect_refusal = [](const CloudFile& cloud, const std::string& fragment,
                                 CloudEncoding encoding = CloudEncoding::kBinary) {
    const std::string path = Dir() + "/refused.las";
    try {
      WriteCloud(path, cloud, encoding);
      ADD_FAILURE() << "written: " << fragment;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(path));
  };
  CloudFile cloud;
  cloud.positions = {{1, 2, 3}, {4, 5, std::numeric_limits<double>::quiet_NaN()}};
  expect_refusal(cloud, "point 1 has a non-finite coordinate");
  cloud.positions[1].z() = 6;
  cloud.intensity = {1.f, 70000.f};
  expect_refusal(cloud, "point 1 has intensity 70000");
  cloud.intensity = {-1.f, 2.f};
  expect_refusal(cloud, "point 0 has intensity -1");
  cloud.intensity.clear();
  cloud.labels = {300, 1};
  expect_refusal(cloud, "label 300");
  cloud.labels = {1, -1};
  expect_refusal(cloud, "label -1");
  cloud.labels.clear();
  expect_refusal(cloud, "binary only", CloudEncoding::kAscii);
  cloud.positions[1].x() = 3e7;  // 30,000 km from the first point
  expect_refusal(cloud, "more than LAS's 32-bit records hold");
  try {
    WriteCloud(Dir() + "/out.laz", cloud);
    ADD_FAILURE() << "LAZ written";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write LAZ"), std::string::npos) << e.what();
  }
}

TEST(Las, ACloudWiderThanTwoHundredKilometresGetsACoarserGrid) {
  CloudFile cloud;
  cloud.positions = {{100000.0, 0.0, 0.0}, {400000.00123, 0.0, 0.0}};
  WriteCloud(Dir() + "/wide.las", cloud);
  const std::vector<uint8_t> b = FileBytes(Dir() + "/wide.las");
  EXPECT_EQ(At<double>(b, 131), 1e-3);  // x: 300 km does not fit 0.1 mm integers
  EXPECT_EQ(At<double>(b, 139), 1e-4);
  EXPECT_NEAR(ReadCloud(Dir() + "/wide.las").positions[1].x(), 400000.001, 1e-9);
}

TEST(Las, ReadInChunksAsAWhole) {
  const std::string path = Dir() + "/chunks.las";
  WriteCloud(path, LasCloud(1000, Eigen::Vector3d(3e5, 4e6, 50.0), 100.0, 9));
  const CloudFile whole = ReadCloud(path);
  for (const std::size_t chunk : {std::size_t{1}, std::size_t{7}, std::size_t{1000}}) {
    std::unique_ptr<CloudStream> stream = CloudStream::Open(path);
    CloudFile all, part;
    std::size_t chunks = 0;
    while (stream->Next(chunk, &part)) {
      all.positions.insert(all.positions.end(), part.positions.begin(), part.positions.end());
      all.labels.insert(all.labels.end(), part.labels.begin(), part.labels.end());
      all.normals.insert(all.normals.end(), part.normals.begin(), part.normals.end());
      ++chunks;
    }
    EXPECT_EQ(chunks, (1000 + chunk - 1) / chunk);
    EXPECT_EQ(all.positions, whole.positions);
    EXPECT_EQ(all.labels, whole.labels);
    EXPECT_EQ(all.normals, whole.normals);
  }
}

// One file per point data record format, records built by hand with extra bytes after each.
class LasFormats : public ::testing::TestWithParam<int> {};

TEST_P(LasFormats, ReadPositionsIntensityAndClassFromTheSpecOffsets) {
  const int format = GetParam();
  const int minor = format >= 6 ? 4 : (format >= 4 ? 3 : 2);
  const std::size_t record_bytes = testing::StandardBytes(format) + 5;  // 5 undescribed bytes
  const Eigen::Vector3d scale(0.01, 0.001, 0.0001), offset(500000.0, 5000000.0, -10.0);
  // Formats 0-5: class 9 with its withheld bit set reads as 9; formats 6-10: all 8 bits.
  const uint8_t cls = format >= 6 ? 200 : 9;
  const std::vector<std::vector<uint8_t>> records = {
      testing::RawRecord(format, record_bytes, 123456, -7, 2147483647, 65535, cls, 0x4),
      testing::RawRecord(format, record_bytes, -2147483647 - 1, 0, 1, 0, 2)};
  const std::string path = Dir() + "/format" + std::to_string(format) + ".las";
  testing::WriteBytes(path, testing::RawLas(minor, format, record_bytes, scale, offset, records,
                                            {std::vector<uint8_t>(17, 0xAB)}));
  const CloudFile read = ReadCloud(path);
  ASSERT_EQ(read.positions.size(), 2u);
  EXPECT_EQ(read.positions[0], Eigen::Vector3d(123456 * 0.01 + 500000.0, -7 * 0.001 + 5000000.0,
                                               2147483647 * 0.0001 - 10.0));
  EXPECT_EQ(read.positions[1].x(), -2147483648.0 * 0.01 + 500000.0);
  EXPECT_EQ(read.intensity, (std::vector<float>{65535.f, 0.f}));
  EXPECT_EQ(read.labels, (std::vector<int32_t>{cls, 2}));
  EXPECT_TRUE(read.normals.empty());
  EXPECT_EQ(ReadCloudInfo(path).points, 2u);
}

INSTANTIATE_TEST_SUITE_P(AllFormats, LasFormats, ::testing::Range(0, 11));

}  // namespace
}  // namespace hylo::io
