// Broken LAS headers, VLRs and EVLRs: every size a file gives is checked against the file before
// anything is allocated, and each break is one line naming the file and what is wrong.

#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "cloud_test_util.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/cloud_stream.h"
#include "las_test_util.h"
#include "test_data.h"

namespace hylo::io {
namespace {

using testing::Put;

std::string Dir() {
  static const std::string dir = hylo::testing::ScratchDir("las_header");
  return dir;
}

// A good 1.4 file from hylo's writer: 375-byte header, no VLR, 4 records of 30 bytes.
std::vector<uint8_t> Good() {
  CloudFile cloud;
  cloud.positions = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {10, 11, 12}};
  const std::string path = Dir() + "/good.las";
  WriteCloud(path, cloud);
  return testing::FileBytes(path);
}

// The bytes written as `name`, then every reader must refuse them in one line naming the file
// and containing `fragment` (header-only reads included).
void ExpectRefused(const std::string& name, const std::vector<uint8_t>& bytes,
                   const std::string& fragment) {
  SCOPED_TRACE(name);
  const std::string path = Dir() + "/" + name;
  testing::WriteBytes(path, bytes);
  const auto check = [&](const std::function<void()>& read) {
    try {
      read();
      ADD_FAILURE() << "accepted";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
    }
  };
  check([&] { ReadCloud(path); });
  check([&] { ReadCloudInfo(path); });
  check([&] { CloudStream::Open(path); });
}

TEST(LasHeader, BrokenFieldsAreOneLineErrors) {
  const std::vector<uint8_t> good = Good();
  std::vector<uint8_t> b = good;
  b[0] = 'X';
  ExpectRefused("signature.las", b, "no 'LASF' signature");
  ExpectRefused("empty.las", {}, "no 'LASF' signature");
  ExpectRefused("short.las", std::vector<uint8_t>(good.begin(), good.begin() + 100),
                "a LAS header alone has 227");
  b = good;
  b[25] = 5;
  ExpectRefused("version.las", b, "LAS 1.5 is not supported");
  b = good;
  Put<uint16_t>(&b, 94, 300);
  ExpectRefused("header_size.las", b, "header size 300 is below the 375 bytes");
  b = good;
  b[104] = 6 | 0x80;
  ExpectRefused("compressed.las", b, "LAZ (compressed LAS) is not supported");
  b = good;
  b[104] = 11;
  ExpectRefused("format.las", b, "unknown point data record format 11");
  b = good;
  Put<uint16_t>(&b, 105, 29);
  ExpectRefused("record.las", b, "point record length 29 is shorter than the 30 bytes");
  b = good;
  Put<double>(&b, 139, 0.0);
  ExpectRefused("scale.las", b, "Y scale factor is 0");
  b = good;
  Put<double>(&b, 171, std::numeric_limits<double>::infinity());
  ExpectRefused("offset.las", b, "Z offset is inf");
  b = good;
  Put<uint32_t>(&b, 96, 100);
  ExpectRefused("inside_header.las", b, "offset to point data 100 lies outside");
  b = good;
  Put<uint32_t>(&b, 96, 100000);
  ExpectRefused("beyond_file.las", b, "offset to point data 100000 lies outside");
}

TEST(LasHeader, CountsAndRecordsBeyondTheFileAreRefusedBeforeAnyAllocation) {
  const std::vector<uint8_t> good = Good();
  std::vector<uint8_t> b = good;
  Put<uint64_t>(&b, 247, 5);
  ExpectRefused("five.las", b, "truncated: 5 points of 30 bytes need 150 bytes");
  Put<uint64_t>(&b, 247, std::numeric_limits<uint64_t>::max());
  ExpectRefused("huge.las", b, "need more than 2^64 bytes");
  ExpectRefused("cut.las", std::vector<uint8_t>(good.begin(), good.end() - 1),
                "truncated: 4 points of 30 bytes need 120 bytes from byte 375, the file has 119");
  // A 1.2 file: its 32-bit count is the only one.
  b = testing::RawLas(2, 0, 20, Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero(),
                      {testing::RawRecord(0, 20, 1, 2, 3, 4, 5)});
  Put<uint32_t>(&b, 107, 4000000000u);
  ExpectRefused("legacy.las", b, "truncated: 4000000000 points of 20 bytes");
}

TEST(LasHeader, VlrsMustFitBeforeThePointData) {
  const std::vector<uint8_t> good =
      testing::RawLas(2, 1, 28, Eigen::Vector3d::Constant(0.01), Eigen::Vector3d::Zero(),
                      {testing::RawRecord(1, 28, 1, 2, 3, 4, 5)}, {{1, 2, 3}, {4, 5}});
  testing::WriteBytes(Dir() + "/vlrs.las", good);
  EXPECT_EQ(ReadCloud(Dir() + "/vlrs.las").positions.size(), 1u);
  std::vector<uint8_t> b = good;
  Put<uint32_t>(&b, 100, 3);  // one more VLR than there is
  ExpectRefused("vlr_count.las", b, "VLR 3 of 3 does not fit");
  Put<uint32_t>(&b, 100, std::numeric_limits<uint32_t>::max());
  ExpectRefused("vlr_count_huge.las", b, "VLR 3 of 4294967295 does not fit");
  b = good;
  Put<uint16_t>(&b, 227 + 20, 60000);  // the first VLR's length runs into the points
  ExpectRefused("vlr_length.las", b, "VLR 1 of 2 does not fit");
}

TEST(LasHeader, EvlrsAreBoundsCheckedAndSkipped) {
  std::vector<uint8_t> good = Good();
  const uint64_t points_end = good.size();
  std::vector<uint8_t> evlr(60, 0);
  Put<uint64_t>(&evlr, 20, 8);
  good.insert(good.end(), evlr.begin(), evlr.end());
  good.resize(good.size() + 8, 0x55);
  Put<uint64_t>(&good, 235, points_end);
  Put<uint32_t>(&good, 243, 1);
  testing::WriteBytes(Dir() + "/evlr.las", good);
  EXPECT_EQ(ReadCloud(Dir() + "/evlr.las").positions.size(), 4u);
  std::vector<uint8_t> b = good;
  Put<uint32_t>(&b, 243, 2);
  ExpectRefused("evlr_count.las", b, "truncated: EVLR 2 of 2 starts at byte");
  b = good;
  Put<uint64_t>(&b, 235, points_end - 1);
  ExpectRefused("evlr_inside.las", b, "the first EVLR starts at byte");
  b = good;
  Put<uint64_t>(&b, points_end + 20, 9);
  ExpectRefused("evlr_length.las", b, "EVLR 1 of 1 announces 9 bytes");
}

TEST(LasHeader, ExtraBytesDescriptorsThatDoNotFitTheRecordAreIgnored) {
  // Normals written by hylo, then the record length cut below what the descriptors describe:
  // the points still read (the extra bytes are only skipped), without normals.
  CloudFile cloud;
  cloud.positions = {{1, 2, 3}};
  cloud.normals = {{0.f, 0.f, 1.f}};
  WriteCloud(Dir() + "/normals.las", cloud);
  std::vector<uint8_t> b = testing::FileBytes(Dir() + "/normals.las");
  EXPECT_EQ(ReadCloud(Dir() + "/normals.las").normals, cloud.normals);
  Put<uint16_t>(&b, 105, 30 + 8);
  b.resize(b.size() - 4);
  testing::WriteBytes(Dir() + "/mismatch.las", b);
  const CloudFile read = ReadCloud(Dir() + "/mismatch.las");
  EXPECT_EQ(read.positions, cloud.positions);
  EXPECT_TRUE(read.normals.empty());
}

TEST(LasHeader, LazIsRefusedWithHowToConvert) {
  testing::WriteBytes(Dir() + "/scan.laz", Good());
  ExpectRefused("scan.laz", Good(), "'laszip -i " + Dir() + "/scan.laz -o " + Dir() + "/scan.las'");
  EXPECT_THROW(CloudStream::Open(Dir() + "/absent.laz"), std::runtime_error);
}

}  // namespace
}  // namespace hylo::io
