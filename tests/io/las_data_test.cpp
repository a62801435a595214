// PDAL's LAS test files (../shared/data/las): every file is either read with the point count,
// scale and offset its header gives (each point checked against its raw bytes, decoded here from
// the specification's offsets), or refused in one line where it is broken. Skipped, visibly,
// without the data.

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>

#include "cloud_test_util.h"
#include "hylo/io/cloud_io.h"
#include "las_test_util.h"
#include "test_data.h"

namespace hylo::io {
namespace {

using testing::FileBytes;
using testing::ParseRawHeader;
using testing::RawLasHeader;

struct Readable {
  std::string version;
  int format;
  uint64_t points;
};

// What each file is (from its header), or why it is refused.
const std::map<std::string, Readable>& ReadableFiles() {
  static const std::map<std::string, Readable> files = {
      {"1.2-with-color.las", {"1.2", 3, 1065}},  {"100-points.las", {"1.2", 3, 100}},
      {"extrabytes.las", {"1.4", 3, 1065}},      {"gps-time-nan.las", {"1.2", 1, 1}},
      {"mvk-thin.las", {"1.2", 1, 6280}},        {"no-points.las", {"1.2", 3, 0}},
      {"permutations_1.0_0.las", {"1.0", 0, 1}}, {"permutations_1.1_1.las", {"1.1", 1, 1}},
      {"permutations_1.2_2.las", {"1.2", 2, 1}}, {"permutations_1.2_3.las", {"1.2", 3, 1}},
      {"simple.las", {"1.2", 3, 1065}},          {"test1_4.las", {"1.4", 6, 1000}},
  };
  return files;
}

const std::map<std::string, std::string>& RefusedFiles() {
  static const std::map<std::string, std::string> files = {
      // Claims 3 VLRs; the third would start where the point data does.
      {"bad_vlr_count.las", "VLR 3 of 3 does not fit between the header and the point data"},
      // Garbage header (VLR count 1069128089, scale 0.00139): 719 records need 6 more bytes.
      {"garbage_nVariableLength.las",
       "truncated: 719 points of 20 bytes need 14380 bytes from byte 227, the file has 14374"},
      {"simple.laz", "LAZ (compressed LAS) is not supported; decompress it first, e.g. 'laszip"},
  };
  return files;
}

std::string Data(const std::string& name) { return hylo::testing::DataPath("las/" + name); }

std::string ErrorOf(const std::function<void()>& read) {
  try {
    read();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

TEST(LasData, EveryFileIsListedAsReadableOrRefused) {
  HYLO_REQUIRE_DATA("las");
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(hylo::testing::DataPath("las"))) {
    const std::string name = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    if (ext != ".las" && ext != ".laz") continue;
    ++files;
    EXPECT_TRUE(ReadableFiles().count(name) + RefusedFiles().count(name) == 1) << name;
  }
  EXPECT_EQ(files, ReadableFiles().size() + RefusedFiles().size());
}

TEST(LasData, ReadableFilesGiveTheirHeadersCountAndEveryPointsRawCoordinates) {
  HYLO_REQUIRE_DATA("las");
  for (const auto& [name, expected] : ReadableFiles()) {
    SCOPED_TRACE(name);
    const std::string path = Data(name);
    const std::vector<uint8_t> bytes = FileBytes(path);
    const RawLasHeader h = ParseRawHeader(bytes);
    ASSERT_EQ(h.points, expected.points);
    const CloudFileInfo info = ReadCloudInfo(path);
    EXPECT_EQ(info.points, expected.points);
    EXPECT_EQ(info.encoding,
              "LAS " + expected.version + " point format " + std::to_string(expected.format));
    const CloudFile cloud = ReadCloud(path);
    ASSERT_EQ(cloud.positions.size(), expected.points);
    ASSERT_EQ(cloud.intensity.size(), expected.points);
    ASSERT_EQ(cloud.labels.size(), expected.points);
    const std::size_t class_byte = h.format >= 6 ? 16 : 15;
    const int class_mask = h.format >= 6 ? 0xFF : 0x1F;
    for (std::size_t i = 0; i < expected.points; ++i) {
      const std::size_t at = h.point_data_offset + i * h.record_bytes;
      ASSERT_EQ(cloud.positions[i], testing::RawPosition(bytes, h, i)) << "point " << i;
      ASSERT_EQ(cloud.intensity[i], testing::At<uint16_t>(bytes, at + 12)) << "point " << i;
      ASSERT_EQ(cloud.labels[i], bytes[at + class_byte] & class_mask) << "point " << i;
    }
  }
}

TEST(LasData, BrokenFilesAreRefusedInOneLine) {
  HYLO_REQUIRE_DATA("las");
  for (const auto& [name, fragment] : RefusedFiles()) {
    SCOPED_TRACE(name);
    const std::string path = Data(name);
    for (const std::string& what :
         {ErrorOf([&] { ReadCloud(path); }), ErrorOf([&] { ReadCloudInfo(path); })}) {
      EXPECT_NE(what.find(path + ": "), std::string::npos) << what;
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(LasData, SimpleLasHoldsWhatItsHeaderPromises) {
  HYLO_REQUIRE_DATA("las/simple.las");
  const CloudFile cloud = ReadCloud(Data("simple.las"));
  ASSERT_EQ(cloud.positions.size(), 1065u);
  // Records 0 and 1064 (X Y Z int32 at bytes 0, 4, 8 of each 34-byte record from byte 227),
  // scale 0.01, offset 0; intensity at byte 12, class in the low 5 bits of byte 15.
  EXPECT_NEAR(cloud.positions[0].x(), 637012.24, 1e-9);
  EXPECT_NEAR(cloud.positions[0].y(), 849028.31, 1e-9);
  EXPECT_NEAR(cloud.positions[0].z(), 431.66, 1e-9);
  EXPECT_EQ(cloud.intensity[0], 143.f);
  EXPECT_NEAR(cloud.positions[1064].x(), 637342.85, 1e-9);
  EXPECT_NEAR(cloud.positions[1064].y(), 853240.32, 1e-9);
  EXPECT_NEAR(cloud.positions[1064].z(), 423.92, 1e-9);
  EXPECT_EQ(cloud.intensity[1064], 116.f);
  std::size_t ground = 0;
  for (const int32_t c : cloud.labels) ground += c == 2;
  EXPECT_EQ(ground, 276u);  // ASPRS class 2; the other 789 are class 1
  // The same points with colour (1.2-with-color) and with 27 extra bytes each (extrabytes, 1.4).
  for (const char* same : {"1.2-with-color.las", "extrabytes.las"}) {
    const CloudFile other = ReadCloud(Data(same));
    EXPECT_EQ(other.positions, cloud.positions) << same;
    EXPECT_EQ(other.intensity, cloud.intensity) << same;
    EXPECT_EQ(other.labels, cloud.labels) << same;
  }
  EXPECT_EQ(ReadCloudInfo(Data("extrabytes.las")).fields.back(), "Time");
}

TEST(LasData, CutFilesAreOneLineErrors) {
  HYLO_REQUIRE_DATA("las/simple.las");
  const std::string dir = hylo::testing::ScratchDir("las_data_cut");
  const std::string full = Data("simple.las");
  testing::Truncate(full, dir + "/half.las", testing::FileSize(full) / 2);
  testing::ExpectReadError(dir + "/half.las", "truncated: 1065 points of 34 bytes");
  testing::Truncate(full, dir + "/header.las", 100);
  testing::ExpectReadError(dir + "/header.las", "truncated: 100 bytes");
}

TEST(LasData, RewrittenByHyloTheyKeepTheirPointsToATenthOfAMillimetre) {
  HYLO_REQUIRE_DATA("las");
  const std::string dir = hylo::testing::ScratchDir("las_data_rewrite");
  for (const char* name : {"simple.las", "test1_4.las", "mvk-thin.las", "no-points.las"}) {
    SCOPED_TRACE(name);
    const CloudFile cloud = ReadCloud(Data(name));
    WriteCloud(dir + "/" + name, cloud);
    const CloudFile again = ReadCloud(dir + "/" + name);
    ASSERT_EQ(again.positions.size(), cloud.positions.size());
    for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
      ASSERT_LE((again.positions[i] - cloud.positions[i]).cwiseAbs().maxCoeff(), 0.5e-4 + 1e-9);
    }
    EXPECT_EQ(again.intensity, cloud.intensity);
    EXPECT_EQ(again.labels, cloud.labels);
  }
}

}  // namespace
}  // namespace hylo::io
