// Cross-checks hylo's PCD/PLY code against PCL (used here only): PCL reads the real data
// files and hylo must agree value for value; each library reads what the other writes.

#include <gtest/gtest.h>
#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include <cmath>
#include <cstring>

#include "cloud_test_util.h"
#include "hylo/io/cloud_io.h"
#include "test_data.h"

namespace hylo::io {
namespace {

// Compares the finite points of a PCL cloud with hylo's reading of the same file.
template <typename PclPoint>
void ExpectSamePoints(const pcl::PointCloud<PclPoint>& expected, const CloudFile& cloud,
                      bool intensity, bool normals) {
  std::size_t j = 0, non_finite = 0;
  for (const PclPoint& p : expected.points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      ++non_finite;
      continue;
    }
    ASSERT_LT(j, cloud.positions.size());
    ASSERT_EQ(cloud.positions[j], Eigen::Vector3d(p.x, p.y, p.z)) << "point " << j;
    if constexpr (std::is_same_v<PclPoint, pcl::PointXYZINormal> ||
                  std::is_same_v<PclPoint, pcl::PointXYZI>) {
      if (intensity) {
        ASSERT_EQ(cloud.intensity[j], p.intensity);
      }
    }
    if constexpr (std::is_same_v<PclPoint, pcl::PointXYZINormal>) {
      if (normals) {
        const Eigen::Vector3f n(p.normal_x, p.normal_y, p.normal_z);
        ASSERT_TRUE(cloud.normals[j] == n || (!n.allFinite() && !cloud.normals[j].allFinite()));
      }
    }
    ++j;
  }
  EXPECT_EQ(j, cloud.positions.size());
  EXPECT_EQ(non_finite, cloud.dropped_non_finite);
}

TEST(PclCrossCheck, BalmBinaryScanWithNormals) {
  HYLO_REQUIRE_DATA("balm_scans/full20.pcd");
  const std::string path = hylo::testing::DataPath("balm_scans/full20.pcd");
  pcl::PointCloud<pcl::PointXYZINormal> expected;
  ASSERT_EQ(pcl::io::loadPCDFile(path, expected), 0);
  const CloudFile cloud = ReadCloud(path);
  EXPECT_EQ(expected.size(), 73082u);
  ExpectSamePoints(expected, cloud, true, true);
}

TEST(PclCrossCheck, IsprsCompressedUtmSamples) {
  for (const char* name : {"isprs/samp11-utm.pcd", "isprs/samp11-utm-ground.pcd",
                           "isprs/samp52-utm.pcd"}) {
    HYLO_REQUIRE_DATA(name);
    const std::string path = hylo::testing::DataPath(name);
    pcl::PointCloud<pcl::PointXYZ> expected;
    ASSERT_EQ(pcl::io::loadPCDFile(path, expected), 0) << name;
    const CloudFile cloud = ReadCloud(path);
    ASSERT_GT(cloud.positions.size(), 1000u) << name;
    ExpectSamePoints(expected, cloud, false, false);
    EXPECT_GT(cloud.positions[0].y(), 1e5) << "UTM northing expected";
  }
}

TEST(PclCrossCheck, VelodyneScanPair) {
  HYLO_REQUIRE_DATA("scan_pair/source.pcd");
  const std::string path = hylo::testing::DataPath("scan_pair/source.pcd");
  pcl::PointCloud<pcl::PointXYZI> expected;
  ASSERT_EQ(pcl::io::loadPCDFile(path, expected), 0);
  ExpectSamePoints(expected, ReadCloud(path), true, false);
}

TEST(PclCrossCheck, CsfSamplePlyWithDoubles) {
  HYLO_REQUIRE_DATA("csf_sample/sample.ply");
  const std::string path = hylo::testing::DataPath("csf_sample/sample.ply");
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPLYFile(path, blob), 0);
  const CloudFile cloud = ReadCloud(path);
  ASSERT_EQ(cloud.positions.size(), 100000u);
  ASSERT_EQ(blob.width * blob.height, 100000u);
  ASSERT_GE(blob.fields.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(blob.fields[k].datatype, pcl::PCLPointField::FLOAT64) << "field " << k;
  }
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      double v = 0;
      std::memcpy(&v, &blob.data[i * blob.point_step + blob.fields[k].offset], sizeof(double));
      ASSERT_EQ(cloud.positions[i][k], v) << "point " << i;
    }
  }
}

class PclReadsHylo : public ::testing::TestWithParam<CloudEncoding> {};

TEST_P(PclReadsHylo, EveryEncoding) {
  const std::string path = hylo::testing::ScratchDir("pcl_reads_hylo") + "/c.pcd";
  CloudFile cloud = testing::RandomCloud(5000, Eigen::Vector3d(3, -4, 1), 9);
  cloud.labels.clear();
  WriteCloud(path, cloud, GetParam());
  pcl::PointCloud<pcl::PointXYZINormal> read;
  ASSERT_EQ(pcl::io::loadPCDFile(path, read), 0);
  CloudFile as_float = cloud;
  for (auto& p : as_float.positions) p = testing::RoundToFloat(p);
  ExpectSamePoints(read, as_float, true, true);
}

INSTANTIATE_TEST_SUITE_P(Encodings, PclReadsHylo,
                         ::testing::Values(CloudEncoding::kAscii, CloudEncoding::kBinary,
                                           CloudEncoding::kBinaryCompressed),
                         [](const auto& info) { return testing::EncodingName(info.param); });

TEST(HyloReadsPcl, BinaryCompressedAndAscii) {
  const std::string dir = hylo::testing::ScratchDir("hylo_reads_pcl");
  pcl::PointCloud<pcl::PointXYZINormal> cloud;
  const CloudFile source = testing::RandomCloud(4000, Eigen::Vector3d(0, 0, 0), 10);
  for (std::size_t i = 0; i < source.positions.size(); ++i) {
    pcl::PointXYZINormal p;
    p.getVector3fMap() = source.positions[i].cast<float>();
    p.intensity = source.intensity[i];
    p.getNormalVector3fMap() = source.normals[i];
    p.curvature = 0.5f;
    cloud.push_back(p);
  }
  cloud.points[7].x = std::numeric_limits<float>::quiet_NaN();
  ASSERT_EQ(pcl::io::savePCDFileBinaryCompressed(dir + "/c.pcd", cloud), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir + "/b.pcd", cloud), 0);
  ExpectSamePoints(cloud, ReadCloud(dir + "/c.pcd"), true, true);
  ExpectSamePoints(cloud, ReadCloud(dir + "/b.pcd"), true, true);
  ASSERT_EQ(pcl::io::savePCDFileASCII(dir + "/a.pcd", cloud), 0);
  const CloudFile ascii = ReadCloud(dir + "/a.pcd");  // PCL prints 8 digits: not exact
  ASSERT_EQ(ascii.positions.size(), cloud.size() - 1);
  EXPECT_EQ(ascii.dropped_non_finite, 1u);
  EXPECT_LT((ascii.positions[100] - cloud.points[101].getVector3fMap().cast<double>()).norm(),
            1e-5);
}

}  // namespace
}  // namespace hylo::io
