// PCD and KITTI .bin reading/writing, and the extension dispatch.

#include "hylo/io/cloud_io.h"

#include <gtest/gtest.h>

#include <limits>

#include "cloud_test_util.h"
#include "test_data.h"

namespace hylo::io {
namespace {

using testing::Append;
using testing::ExpectReadError;
using testing::RandomCloud;
using testing::WriteRaw;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Asserts equality where positions are compared after the storage precision `position_type`.
template <typename PositionType>
void ExpectSameCloud(const CloudFile& written, const CloudFile& read) {
  ASSERT_EQ(read.positions.size(), written.positions.size());
  ASSERT_EQ(read.intensity.size(), written.intensity.size());
  ASSERT_EQ(read.normals.size(), written.normals.size());
  ASSERT_EQ(read.labels.size(), written.labels.size());
  for (std::size_t i = 0; i < written.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(read.positions[i][k],
                static_cast<double>(static_cast<PositionType>(written.positions[i][k])))
          << "point " << i;
    }
    if (!written.intensity.empty()) {
      ASSERT_EQ(read.intensity[i], written.intensity[i]);
    }
    if (!written.normals.empty()) {
      ASSERT_EQ(read.normals[i], written.normals[i]);
    }
    if (!written.labels.empty()) {
      ASSERT_EQ(read.labels[i], written.labels[i]);
    }
  }
}

class PcdRoundTrip : public ::testing::TestWithParam<CloudEncoding> {};

TEST_P(PcdRoundTrip, SmallCoordinatesAsFloatWithAllAttributes) {
  const std::string path = hylo::testing::ScratchDir("pcd_rt_small") + "/cloud.pcd";
  const CloudFile cloud = RandomCloud(2000, Eigen::Vector3d(1, 2, 3), 1);
  WriteCloud(path, cloud, GetParam());
  const CloudFileInfo info = ReadCloudInfo(path);
  EXPECT_EQ(info.points, 2000u);
  EXPECT_EQ(info.fields, (std::vector<std::string>{"x", "y", "z", "intensity", "normal_x",
                                                    "normal_y", "normal_z", "label"}));
  const CloudFile read = ReadCloud(path);
  EXPECT_EQ(read.dropped_non_finite, 0u);
  ExpectSameCloud<float>(cloud, read);
}

TEST_P(PcdRoundTrip, UtmCoordinatesKeepDoublePrecision) {
  const std::string path = hylo::testing::ScratchDir("pcd_rt_utm") + "/cloud.pcd";
  CloudFile cloud = RandomCloud(500, Eigen::Vector3d(394627.7181, 5640509.5123, 799.65), 2);
  cloud.normals.clear();
  cloud.labels.clear();
  WriteCloud(path, cloud, GetParam());
  const CloudFile read = ReadCloud(path);
  ExpectSameCloud<double>(cloud, read);
  EXPECT_TRUE(read.normals.empty());
  EXPECT_TRUE(read.labels.empty());
}

TEST_P(PcdRoundTrip, PositionsOnlyAndEmptyCloud) {
  const std::string dir = hylo::testing::ScratchDir("pcd_rt_plain");
  CloudFile cloud;
  cloud.positions = {{0.5, -1.25, 3.0}, {1e-7, 2e4, -7.5}};  // 2e4 is exact in float
  WriteCloud(dir + "/a.pcd", cloud, GetParam());
  ExpectSameCloud<float>(cloud, ReadCloud(dir + "/a.pcd"));
  WriteCloud(dir + "/empty.pcd", CloudFile{}, GetParam());
  EXPECT_TRUE(ReadCloud(dir + "/empty.pcd").positions.empty());
}

INSTANTIATE_TEST_SUITE_P(Encodings, PcdRoundTrip,
                         ::testing::Values(CloudEncoding::kAscii, CloudEncoding::kBinary,
                                           CloudEncoding::kBinaryCompressed),
                         [](const auto& info) { return testing::EncodingName(info.param); });

TEST(Pcd, CompressedFileIsSmallerOnStructuredData) {
  const std::string dir = hylo::testing::ScratchDir("pcd_compress_size");
  CloudFile cloud;
  for (int i = 0; i < 10000; ++i) cloud.positions.emplace_back(i % 100, i / 100, 0.0);
  WriteCloud(dir + "/b.pcd", cloud, CloudEncoding::kBinary);
  WriteCloud(dir + "/c.pcd", cloud, CloudEncoding::kBinaryCompressed);
  EXPECT_LT(testing::FileSize(dir + "/c.pcd"), testing::FileSize(dir + "/b.pcd") / 2);
}

std::string PcdHeader(const std::string& fields, const std::string& size, const std::string& type,
                      const std::string& count, int width, int height, const std::string& data) {
  return "# .PCD v0.7\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " + type +
         "\nCOUNT " + count + "\nWIDTH " + std::to_string(width) + "\nHEIGHT " +
         std::to_string(height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
         std::to_string(width * height) + "\nDATA " + data + "\n";
}

TEST(Pcd, ReadsAnyFieldOrderTypesCountsAndOrganizedClouds) {
  // 2 x 2 organized cloud; fields in an odd order, a COUNT 3 field to skip, mixed types.
  const std::string path = hylo::testing::ScratchDir("pcd_types") + "/odd.pcd";
  std::vector<uint8_t> body;
  for (int i = 0; i < 4; ++i) {
    Append<uint16_t>(&body, static_cast<uint16_t>(1000 + i));  // label U2
    for (int k = 0; k < 3; ++k) Append<float>(&body, 9.f);      // rgb-like COUNT 3, skipped
    Append<double>(&body, 0.1 * i);                              // z F8
    Append<int8_t>(&body, static_cast<int8_t>(-i));              // x I1
    Append<float>(&body, i == 2 ? kNaN : 2.5f * i);              // y F4 (one NaN)
    Append<uint8_t>(&body, static_cast<uint8_t>(200 + i));       // intensity U1
  }
  WriteRaw(path, PcdHeader("label junk z x y intensity", "2 4 8 1 4 1", "U F F I F U",
                           "1 3 1 1 1 1", 2, 2, "binary"), body);
  const CloudFile cloud = ReadCloud(path);
  ASSERT_EQ(cloud.positions.size(), 3u);
  EXPECT_EQ(cloud.dropped_non_finite, 1u);
  const int kept[3] = {0, 1, 3};
  for (int j = 0; j < 3; ++j) {
    const int i = kept[j];
    EXPECT_EQ(cloud.positions[j], Eigen::Vector3d(-i, 2.5 * i, 0.1 * i));
    EXPECT_EQ(cloud.intensity[j], 200.f + i);
    EXPECT_EQ(cloud.labels[j], 1000 + i);
  }
  EXPECT_TRUE(cloud.normals.empty());
}

TEST(Pcd, AsciiReadsNanAndUnsignedLabels) {
  const std::string path = hylo::testing::ScratchDir("pcd_ascii") + "/a.pcd";
  WriteRaw(path, PcdHeader("x y z label", "4 4 4 4", "F F F U", "1 1 1 1", 4, 1, "ascii") +
                     "1 2 3 7\nnan 2 3 8\n\n4 5 inf 9\n-1.5 2e3 0 4294967295\n");
  const CloudFile cloud = ReadCloud(path);
  ASSERT_EQ(cloud.positions.size(), 2u);
  EXPECT_EQ(cloud.dropped_non_finite, 2u);
  EXPECT_EQ(cloud.positions[1], Eigen::Vector3d(-1.5, 2000, 0));
  EXPECT_EQ(cloud.labels, (std::vector<int32_t>{7, -1}));  // 0xFFFFFFFF wraps to -1
}

TEST(Pcd, TruncatedFilesAreErrorsInEveryEncoding) {
  const std::string dir = hylo::testing::ScratchDir("pcd_truncated");
  const CloudFile cloud = RandomCloud(300, Eigen::Vector3d::Zero(), 3);
  const std::pair<CloudEncoding, const char*> cases[] = {
      {CloudEncoding::kAscii, "a"}, {CloudEncoding::kBinary, "b"},
      {CloudEncoding::kBinaryCompressed, "c"}};
  for (const auto& [encoding, name] : cases) {
    const std::string full = dir + "/" + name + ".pcd";
    const std::string cut = dir + "/" + name + "_cut.pcd";
    WriteCloud(full, cloud, encoding);
    testing::Truncate(full, cut, testing::FileSize(full) - 40);
    ExpectReadError(cut, "truncated");
  }
}

TEST(Pcd, MalformedHeadersAreErrors) {
  const std::string dir = hylo::testing::ScratchDir("pcd_malformed");
  WriteRaw(dir + "/nodata.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\n");
  ExpectReadError(dir + "/nodata.pcd", "no DATA");
  WriteRaw(dir + "/sizes.pcd", PcdHeader("x y z", "4 4", "F F F", "1 1 1", 1, 1, "ascii"));
  ExpectReadError(dir + "/sizes.pcd", "disagree");
  WriteRaw(dir + "/type.pcd", PcdHeader("x y z", "4 4 2", "F F F", "1 1 1", 1, 1, "ascii"));
  ExpectReadError(dir + "/type.pcd", "unsupported TYPE");
  WriteRaw(dir + "/points.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nHEIGHT 1\n"
                                "POINTS 3\nDATA ascii\n");
  ExpectReadError(dir + "/points.pcd", "POINTS");
  WriteRaw(dir + "/noxyz.pcd", PcdHeader("x y intensity", "4 4 4", "F F F", "1 1 1", 1, 1,
                                         "ascii") + "1 2 3\n");
  ExpectReadError(dir + "/noxyz.pcd", "no x, y and z");
  WriteRaw(dir + "/row.pcd", PcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "ascii") +
                                 "1 2 3\n4 5\n");
  ExpectReadError(dir + "/row.pcd", "line 2");
  WriteRaw(dir + "/lzf.pcd", PcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 1, 1,
                                       "binary_compressed"),
           {4, 0, 0, 0, 12, 0, 0, 0, 3, 'a', 'b', 'c'});  // expands to 4 bytes, not 12
  ExpectReadError(dir + "/lzf.pcd", "corrupt");
}

TEST(CloudIo, MissingFileAndUnknownExtensionAreErrors) {
  const std::string dir = hylo::testing::ScratchDir("cloud_io_errors");
  ExpectReadError(dir + "/absent.pcd", "cannot open");
  ExpectReadError(dir + "/absent.ply", "cannot open");
  WriteRaw(dir + "/cloud.xyz", "1 2 3\n");
  ExpectReadError(dir + "/cloud.xyz", "unknown point cloud extension");
  EXPECT_THROW(WriteCloud(dir + "/cloud.xyz", CloudFile{}), std::runtime_error);
  EXPECT_THROW(WriteCloud(dir + "/cloud.laz", CloudFile{}), std::runtime_error);  // LAZ: not written
  CloudFile bad;
  bad.positions = {{1, 2, 3}};
  bad.intensity = {1.f, 2.f};
  EXPECT_THROW(WriteCloud(dir + "/bad.pcd", bad), std::runtime_error);
}

TEST(KittiBin, RoundTripsAndCountsNan) {
  const std::string dir = hylo::testing::ScratchDir("kitti_bin");
  CloudFile cloud = RandomCloud(100, Eigen::Vector3d::Zero(), 4);
  cloud.normals.clear();
  EXPECT_THROW(WriteCloud(dir + "/labels.bin", cloud), std::runtime_error);  // cannot hold
  cloud.labels.clear();
  cloud.positions[10].y() = std::numeric_limits<double>::infinity();
  WriteCloud(dir + "/000000.bin", cloud);
  EXPECT_EQ(testing::FileSize(dir + "/000000.bin"), 100u * 16u);
  const CloudFile read = ReadCloud(dir + "/000000.bin");
  EXPECT_EQ(read.dropped_non_finite, 1u);
  cloud.positions.erase(cloud.positions.begin() + 10);
  cloud.intensity.erase(cloud.intensity.begin() + 10);
  cloud.dropped_non_finite = 1;
  ExpectSameCloud<float>(cloud, read);
  testing::Truncate(dir + "/000000.bin", dir + "/cut.bin", 100 * 16 - 3);
  ExpectReadError(dir + "/cut.bin", "truncated");
  EXPECT_THROW(WriteCloud(dir + "/a.bin", cloud, CloudEncoding::kAscii), std::runtime_error);
}

}  // namespace
}  // namespace hylo::io
