// Reading point cloud files in chunks: every format and encoding gives, chunk by chunk, exactly
// what a whole-file read gives; the streamed LZF decoder agrees with liblzf on good and corrupt
// blocks; the chunked PCD writer writes a file only when committed.

#include "hylo/io/cloud_stream.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

#include "cloud_test_util.h"
#include "test_data.h"

namespace hylo::io {
namespace {

using testing::ExpectReadError;
using testing::RandomCloud;

struct Case {
  std::string file;
  CloudEncoding encoding;
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

// Concatenates the chunks of `path` read `chunk` records at a time.
CloudFile Streamed(const std::string& path, std::size_t chunk, std::size_t* chunks = nullptr) {
  std::unique_ptr<CloudStream> stream = CloudStream::Open(path);
  CloudFile all, part;
  std::size_t n = 0;
  while (stream->Next(chunk, &part)) {
    EXPECT_LE(part.positions.size() + part.dropped_non_finite, chunk);
    all.positions.insert(all.positions.end(), part.positions.begin(), part.positions.end());
    all.intensity.insert(all.intensity.end(), part.intensity.begin(), part.intensity.end());
    all.normals.insert(all.normals.end(), part.normals.begin(), part.normals.end());
    all.labels.insert(all.labels.end(), part.labels.begin(), part.labels.end());
    all.dropped_non_finite += part.dropped_non_finite;
    ++n;
  }
  EXPECT_EQ(stream->records_read(), stream->info().points);
  if (chunks != nullptr) *chunks = n;
  return all;
}

class StreamMatchesWholeRead : public ::testing::TestWithParam<Case> {};

TEST_P(StreamMatchesWholeRead, ForAnyChunkSize) {
  const std::string path = hylo::testing::ScratchDir("cloud_stream") + "/" + GetParam().file;
  CloudFile cloud = RandomCloud(1000, Eigen::Vector3d(5e5, 4e6, 100.0), 11);
  if (path.size() > 4 && path.substr(path.size() - 4) == ".bin") {
    cloud.normals.clear();
    cloud.labels.clear();
  }
  cloud.positions[17].x() = std::numeric_limits<double>::quiet_NaN();
  cloud.positions[999].z() = std::numeric_limits<double>::infinity();
  WriteCloud(path, cloud, GetParam().encoding);
  const CloudFile whole = ReadCloud(path);
  ASSERT_EQ(whole.positions.size(), 998u);
  ASSERT_EQ(whole.dropped_non_finite, 2u);
  for (const std::size_t chunk :
       {std::size_t{1}, std::size_t{7}, std::size_t{1000}, std::size_t{5000}}) {
    std::size_t chunks = 0;
    const CloudFile streamed = Streamed(path, chunk, &chunks);
    EXPECT_EQ(chunks, (1000 + chunk - 1) / chunk) << "chunk " << chunk;
    EXPECT_EQ(streamed.positions, whole.positions) << "chunk " << chunk;
    EXPECT_EQ(streamed.intensity, whole.intensity) << "chunk " << chunk;
    EXPECT_EQ(streamed.normals, whole.normals) << "chunk " << chunk;
    EXPECT_EQ(streamed.labels, whole.labels) << "chunk " << chunk;
    EXPECT_EQ(streamed.dropped_non_finite, 2u) << "chunk " << chunk;
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, StreamMatchesWholeRead,
                         ::testing::Values(Case{"a.pcd", CloudEncoding::kAscii},
                                           Case{"b.pcd", CloudEncoding::kBinary},
                                           Case{"c.pcd", CloudEncoding::kBinaryCompressed},
                                           Case{"a.ply", CloudEncoding::kAscii},
                                           Case{"b.ply", CloudEncoding::kBinary},
                                           Case{"k.bin", CloudEncoding::kBinary}),
                         [](const auto& info) {
                           std::string name = info.param.file;
                           name[name.find('.')] = '_';
                           return name;
                         });

void ExpectStreamError(const std::string& path, const std::string& fragment) {
  try {
    Streamed(path, 64);
    ADD_FAILURE() << "no error for " << path;
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(CloudStream, CorruptAndTruncatedCompressedBlocksAreErrors) {
  const std::string dir = hylo::testing::ScratchDir("cloud_stream_bad");
  const CloudFile cloud = RandomCloud(300, Eigen::Vector3d::Zero(), 5);
  const std::string full = dir + "/c.pcd";
  WriteCloud(full, cloud, CloudEncoding::kBinaryCompressed);
  testing::Truncate(full, dir + "/cut.pcd", testing::FileSize(full) - 40);
  ExpectStreamError(dir + "/cut.pcd", "truncated");
  // A back reference before the start of the output: control byte 0x20 (length 1) with
  // offset 1 at output position 0.
  const std::string header =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\n"
      "POINTS 1\nDATA binary_compressed\n";
  testing::WriteRaw(dir + "/ref.pcd", header, {2, 0, 0, 0, 12, 0, 0, 0, 0x20, 0x00});
  ExpectStreamError(dir + "/ref.pcd", "corrupt");
  ExpectReadError(dir + "/ref.pcd", "corrupt");  // liblzf says the same
  // A stream that ends before the 12 bytes it must expand to.
  testing::WriteRaw(dir + "/short.pcd", header, {4, 0, 0, 0, 12, 0, 0, 0, 2, 'a', 'b', 'c'});
  ExpectStreamError(dir + "/short.pcd", "corrupt");
  ExpectReadError(dir + "/short.pcd", "corrupt");
}

TEST(CloudStream, MissingFilesAndHeadersWithoutXyzFailAtOpen) {
  const std::string dir = hylo::testing::ScratchDir("cloud_stream_open");
  EXPECT_THROW(CloudStream::Open(dir + "/absent.pcd"), std::runtime_error);
  EXPECT_THROW(CloudStream::Open(dir + "/cloud.xyz"), std::runtime_error);
  testing::WriteRaw(dir + "/noz.pcd", "FIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 1\nDATA ascii\n1 2\n");
  EXPECT_THROW(CloudStream::Open(dir + "/noz.pcd"), std::runtime_error);
}

TEST(PcdXyzWriter, WritesOnlyWhenCommitted) {
  const std::string dir = hylo::testing::ScratchDir("pcd_xyz_writer");
  PointCloud a = {{1.f, 2.f, 3.f}, {4.f, 5.f, 6.f}};
  PointCloud b = {{-7.5f, 8.25f, 1e4f}};
  {
    PcdXyzWriter abandoned(dir + "/abandoned.pcd");
    abandoned.Add(a);
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));  // neither the file nor its body left
  PcdXyzWriter writer(dir + "/xyz.pcd");
  writer.Add(a);
  writer.Add({});
  writer.Add(b);
  writer.Commit();
  EXPECT_EQ(writer.points(), 3u);
  std::size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);  // no body file left behind
  const CloudFile read = ReadCloud(dir + "/xyz.pcd");
  ASSERT_EQ(read.positions.size(), 3u);
  EXPECT_EQ(read.positions[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(read.positions[2], Eigen::Vector3d(-7.5, 8.25, 1e4));
}

}  // namespace
}  // namespace hylo::io
