// PLY reading and writing: ascii, binary little- and big-endian, other elements skipped.

#include <gtest/gtest.h>

#include <limits>

#include "cloud_test_util.h"
#include "hylo/io/cloud_io.h"
#include "test_data.h"

namespace hylo::io {
namespace {

using testing::Append;
using testing::ExpectReadError;
using testing::WriteRaw;

class PlyRoundTrip : public ::testing::TestWithParam<CloudEncoding> {};

TEST_P(PlyRoundTrip, KeepsValuesAndAttributes) {
  const std::string dir = hylo::testing::ScratchDir("ply_rt");
  struct Case {
    Eigen::Vector3d center;
    bool stored_as_double;
  };
  const std::vector<Case> cases = {{Eigen::Vector3d(1, 2, 3), false},
                                   {Eigen::Vector3d(5e5, 4e6, 300), true}};
  for (const Case& c : cases) {
    const CloudFile cloud = testing::RandomCloud(777, c.center, 5);
    WriteCloud(dir + "/c.ply", cloud, GetParam());
    const CloudFile read = ReadCloud(dir + "/c.ply");
    ASSERT_EQ(read.positions.size(), cloud.positions.size());
    for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
      const Eigen::Vector3d& original = cloud.positions[i];
      for (int k = 0; k < 3; ++k) {
        const double expected = c.stored_as_double ? original[k]
                                                   : static_cast<float>(original[k]);
        ASSERT_EQ(read.positions[i][k], expected) << "point " << i << " double "
                                                  << c.stored_as_double;
      }
      ASSERT_EQ(read.normals[i], cloud.normals[i]);
      ASSERT_EQ(read.intensity[i], cloud.intensity[i]);
      ASSERT_EQ(read.labels[i], cloud.labels[i]);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Encodings, PlyRoundTrip,
                         ::testing::Values(CloudEncoding::kAscii, CloudEncoding::kBinary),
                         [](const auto& info) { return testing::EncodingName(info.param); });

TEST(Ply, CompressedEncodingIsRefused) {
  const std::string dir = hylo::testing::ScratchDir("ply_refuse");
  EXPECT_THROW(WriteCloud(dir + "/c.ply", CloudFile{}, CloudEncoding::kBinaryCompressed),
               std::runtime_error);
}

// A big-endian file with an element before the vertices (with a list) and faces after.
TEST(Ply, ReadsBigEndianSkippingOtherElementsAndScalarFields) {
  const std::string path = hylo::testing::ScratchDir("ply_be") + "/be.ply";
  const std::string header =
      "ply\nformat binary_big_endian 1.0\ncomment test\n"
      "element camera 1\nproperty list uchar int ids\nproperty float f\n"
      "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "property uchar red\nproperty float scalar_Intensity\nproperty short nx\n"
      "property short ny\nproperty short nz\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::vector<uint8_t> body;
  Append<uint8_t>(&body, 2);
  Append<int32_t>(&body, 11, true);
  Append<int32_t>(&body, 12, true);
  Append<float>(&body, 1.5f, true);
  for (int i = 0; i < 3; ++i) {
    Append<double>(&body, 400000.125 + i, true);
    Append<double>(&body, i == 1 ? std::numeric_limits<double>::quiet_NaN() : -2.5, true);
    Append<double>(&body, 0.001 * i, true);
    Append<uint8_t>(&body, 255);
    Append<float>(&body, 10.f * i, true);
    for (int k = 0; k < 3; ++k) Append<int16_t>(&body, static_cast<int16_t>(k - i), true);
  }
  Append<uint8_t>(&body, 3);
  for (int k = 0; k < 3; ++k) Append<int32_t>(&body, k, true);
  WriteRaw(path, header, body);
  const CloudFile cloud = ReadCloud(path);
  ASSERT_EQ(cloud.positions.size(), 2u);
  EXPECT_EQ(cloud.dropped_non_finite, 1u);
  EXPECT_EQ(cloud.positions[1], Eigen::Vector3d(400002.125, -2.5, 0.002));
  EXPECT_EQ(cloud.intensity, (std::vector<float>{0.f, 20.f}));
  EXPECT_EQ(cloud.normals[1], Eigen::Vector3f(-2, -1, 0));
  EXPECT_TRUE(cloud.labels.empty());
  const CloudFileInfo info = ReadCloudInfo(path);
  EXPECT_EQ(info.points, 3u);
  EXPECT_EQ(info.encoding, "binary_big_endian");
  EXPECT_EQ(info.fields.size(), 8u);
}

TEST(Ply, AsciiWithFacesAndComments) {
  const std::string path = hylo::testing::ScratchDir("ply_ascii") + "/a.ply";
  WriteRaw(path, "ply\r\nformat ascii 1.0\r\nobj_info x\r\nelement vertex 2\r\n"
                 "property float x\r\nproperty float y\r\nproperty float z\r\n"
                 "element face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
                 "0.1 0.2 0.3\r\n4 5 6\r\n3 0 1 1\r\n");
  const CloudFile cloud = ReadCloud(path);
  ASSERT_EQ(cloud.positions.size(), 2u);
  EXPECT_EQ(cloud.positions[0], Eigen::Vector3f(0.1f, 0.2f, 0.3f).cast<double>());
  EXPECT_TRUE(cloud.intensity.empty());
}

TEST(Ply, BadFilesAreErrors) {
  const std::string dir = hylo::testing::ScratchDir("ply_bad");
  WriteRaw(dir + "/magic.ply", "plx\nformat ascii 1.0\nend_header\n");
  ExpectReadError(dir + "/magic.ply", "does not start with 'ply'");
  WriteRaw(dir + "/type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\n"
                              "end_header\n");
  ExpectReadError(dir + "/type.ply", "unknown PLY type");
  WriteRaw(dir + "/end.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n");
  ExpectReadError(dir + "/end.ply", "no end_header");
  WriteRaw(dir + "/noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                             "property float y\nend_header\n1 2\n");
  ExpectReadError(dir + "/noz.ply", "no x, y and z");
  WriteRaw(dir + "/short.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                               "property float y\nproperty float z\nend_header\n1 2 3\n4 5 6\n");
  ExpectReadError(dir + "/short.ply", "truncated");
  const CloudFile cloud = testing::RandomCloud(50, Eigen::Vector3d::Zero(), 6);
  WriteCloud(dir + "/full.ply", cloud, CloudEncoding::kBinary);
  testing::Truncate(dir + "/full.ply", dir + "/cut.ply", testing::FileSize(dir + "/full.ply") - 1);
  ExpectReadError(dir + "/cut.ply", "truncated");
}

}  // namespace
}  // namespace hylo::io
