// Costmap exports: the PNG is decoded back with libpng and compared pixel by pixel; the PGM is
// read back through map_server's trinary rule; ASCII grids round-trip, UTM origins included.
#include "hylo/io/costmap_io.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

namespace hylo::io {
namespace {

using terrain::CellClass;
using terrain::GridGeometry;
using terrain::GridMap;
namespace fs = std::filesystem;

std::string TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("hylo_costmap_io_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

struct DecodedPng {
  uint32_t width = 0, height = 0;
  bool rgb8 = false;  ///< the file's own format: 8-bit RGB, no alpha, no palette
  std::vector<uint8_t> rgb;
};

/// Decodes with libpng (its checks: signature, chunk CRCs, zlib stream); a file libpng rejects
/// fails the calling test.
DecodedPng DecodePng(const std::string& png) {
  DecodedPng out;
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, png.data(), png.size())) {
    ADD_FAILURE() << "libpng: " << image.message;
    return out;
  }
  out.width = image.width;
  out.height = image.height;
  out.rgb8 = image.format == PNG_FORMAT_RGB;
  image.format = PNG_FORMAT_RGB;
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) {
    ADD_FAILURE() << "libpng: " << image.message;
    out.rgb.clear();
  }
  return out;
}

TEST(EncodePngRgb, DecodesToTheSamePixels) {
  std::mt19937 rng(5);
  for (const auto& [w, h] : {std::pair<int, int>{1, 1}, {3, 2}, {300, 200}}) {
    std::vector<uint8_t> rgb(w * h * 3);
    for (auto& v : rgb) v = static_cast<uint8_t>(rng());
    const DecodedPng png = DecodePng(EncodePngRgb(w, h, rgb));
    EXPECT_EQ(png.width, static_cast<uint32_t>(w));
    EXPECT_EQ(png.height, static_cast<uint32_t>(h));
    EXPECT_TRUE(png.rgb8);
    EXPECT_EQ(png.rgb, rgb);
  }
  EXPECT_THROW(EncodePngRgb(2, 2, std::vector<uint8_t>(5)), std::invalid_argument);
  EXPECT_THROW(EncodePngRgb(0, 2, {}), std::invalid_argument);
}

TEST(EncodePngRgb, CompressesAFlatCostmap) {
  const std::vector<uint8_t> grey(400 * 300 * 3, 128);  // a costmap of unknown cells
  const std::string png = EncodePngRgb(400, 300, grey);
  EXPECT_LT(png.size(), grey.size() / 50);
  EXPECT_EQ(DecodePng(png).rgb, grey);
}

/// 3 x 2 grid at a UTM origin: row 0 = free, cost, lethal; row 1 = unknown, free, cost.
GridMap SmallCostGrid(std::vector<CellClass>* classes) {
  GridGeometry g;
  g.origin_world = {523400.0, 4181200.0, 241.0};
  g.corner_local = {0.25, -0.5};
  g.resolution_m = 0.25;
  g.width = 3;
  g.height = 2;
  GridMap grid(g);
  grid.AddLayer(terrain::layers::kCost, 0.f) = {0.1f, 0.6f, 1.f, NAN, 0.f, 0.9f};
  *classes = {CellClass::kFree,    CellClass::kCost, CellClass::kLethal,
              CellClass::kUnknown, CellClass::kFree, CellClass::kCost};
  return grid;
}

TEST(WriteCostmapPng, ColoursAndNorthUp) {
  std::vector<CellClass> classes;
  const GridMap grid = SmallCostGrid(&classes);
  const std::string path = TempDir("png") + "/costmap.png";
  WriteCostmapPng(path, grid, classes);
  const DecodedPng png = DecodePng(ReadAll(path));
  ASSERT_EQ(png.rgb.size(), 18u);
  auto pixel = [&](int x, int y) {
    return std::vector<int>(png.rgb.begin() + (y * 3 + x) * 3,
                            png.rgb.begin() + (y * 3 + x) * 3 + 3);
  };
  EXPECT_EQ(pixel(0, 0), (std::vector<int>{128, 128, 128}));  // top row = grid row 1: unknown
  EXPECT_EQ(pixel(1, 0), (std::vector<int>{0, 170, 0}));      // cost 0: green
  EXPECT_EQ(pixel(2, 1), (std::vector<int>{0, 0, 0}));        // lethal: black
  const std::vector<int> costly = pixel(2, 0);                // cost 0.9: towards red
  EXPECT_GT(costly[0], 200);
  EXPECT_LT(costly[1], 60);
}

std::map<std::string, std::string> ReadYaml(const std::string& path) {
  std::map<std::string, std::string> kv;
  std::istringstream in(ReadAll(path));
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto colon = line.find(':');
    kv[line.substr(0, colon)] = line.substr(colon + 2);
  }
  return kv;
}

TEST(WriteMapServer, TrinaryReadingGivesClassesAndOriginKeepsUtmDigits) {
  std::vector<CellClass> classes;
  const GridMap grid = SmallCostGrid(&classes);
  const std::string yaml = TempDir("pgm") + "/site.yaml";
  WriteMapServer(yaml, grid, classes);
  const auto kv = ReadYaml(yaml);
  EXPECT_EQ(kv.at("image"), "site.pgm");
  EXPECT_EQ(kv.at("resolution"), "0.25");
  EXPECT_EQ(kv.at("origin"), "[523400.250000, 4181199.500000, 0.0]");
  EXPECT_EQ(kv.at("negate"), "0");
  EXPECT_EQ(kv.at("mode"), "trinary");
  const double occupied = std::stod(kv.at("occupied_thresh")),
               free = std::stod(kv.at("free_thresh"));
  // The PGM: header (with a comment line), then 6 pixels, north row first.
  std::istringstream pgm(ReadAll(fs::path(yaml).replace_extension(".pgm").string()));
  std::string magic, comment;
  int w, h, maxval;
  pgm >> magic >> std::ws;
  std::getline(pgm, comment);
  pgm >> w >> h >> maxval;
  pgm.get();
  ASSERT_EQ(magic, "P5");
  EXPECT_EQ(comment[0], '#');
  ASSERT_EQ(w * 10 + h, 32);
  std::string pixels(6, '\0');
  pgm.read(&pixels[0], 6);
  // map_server's trinary rule (negate 0): occupancy (255 - p) / 255.
  const int kExpected[6] = {-1, 0, 0, 0, 0, 100};  // north row: unknown, free, cost; then
  for (int i = 0; i < 6; ++i) {                    // free, cost, lethal
    const double occ = (255 - static_cast<unsigned char>(pixels[i])) / 255.0;
    const int value = occ > occupied ? 100 : occ < free ? 0 : -1;
    EXPECT_EQ(value, kExpected[i]) << "pixel " << i;
  }
  // The cost grade survives as darker grey for costlier (still free) cells.
  EXPECT_LT(static_cast<unsigned char>(pixels[2]), static_cast<unsigned char>(pixels[1]));
  MapServerOptions bad;
  bad.free_thresh = 0.25;
  EXPECT_THROW(WriteMapServer(yaml, grid, classes, bad), std::invalid_argument);
  EXPECT_THROW(WriteMapServer("/nonexistent_dir/x.yaml", grid, classes), std::runtime_error);
}

TEST(AsciiGrid, RoundTripWithNoDataOffsetAndUtmCorner) {
  std::vector<CellClass> classes;
  GridMap grid = SmallCostGrid(&classes);
  grid.AddLayer(terrain::layers::kElevation, 0.f) = {0.123f, -1.5f, NAN, 2.25f, 0.f, 3.f};
  const std::string path = TempDir("asc") + "/elevation.asc";
  WriteAsciiGrid(path, grid, terrain::layers::kElevation, grid.geometry().origin_world.z());
  const GridMap back = ReadAsciiGrid(path, "z");
  const GridGeometry& g = back.geometry();
  EXPECT_EQ(g.width, 3);
  EXPECT_EQ(g.height, 2);
  EXPECT_DOUBLE_EQ(g.resolution_m, 0.25);
  EXPECT_NEAR(g.CornerWorld().x(), 523400.25, 1e-6);
  EXPECT_NEAR(g.CornerWorld().y(), 4181199.5, 1e-6);
  const auto& z = back.Layer("z");
  const auto& original = grid.Layer(terrain::layers::kElevation);
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (std::isnan(original[i])) {
      EXPECT_TRUE(std::isnan(z[i]));
    } else {
      EXPECT_NEAR(z[i], original[i] + 241.0, 1e-4) << i;
    }
  }
}

TEST(AsciiGrid, BadFilesNameTheReason) {
  const std::string dir = TempDir("bad_asc");
  auto expect_error = [&](const std::string& text, const std::string& reason) {
    std::ofstream(dir + "/g.asc") << text;
    try {
      ReadAsciiGrid(dir + "/g.asc", "v");
      ADD_FAILURE() << "expected an error for: " << reason;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("g.asc"), std::string::npos) << e.what();
    }
  };
  expect_error("ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\n1 2\n", "cellsize");
  expect_error("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n", "expected 4");
  EXPECT_THROW(ReadAsciiGrid(dir + "/missing.asc", "v"), std::runtime_error);
}

TEST(WriteTraversabilityFiles, WritesEveryOutputWithWorldHeights) {
  std::vector<Eigen::Vector3d> ground;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j) ground.emplace_back(612000.013 + 0.05 * i, 5.2e6 + 0.05 * j, 87.5);
  terrain::TraversabilityOptions options;
  options.resolution_m = 0.25;
  const terrain::TraversabilityMap map = terrain::ComputeTraversability(ground, {}, options);
  const std::string dir = TempDir("all");
  const std::vector<std::string> files = WriteTraversabilityFiles(dir, map);
  for (const std::string& f : files) EXPECT_TRUE(fs::exists(f)) << f;
  EXPECT_TRUE(fs::exists(dir + "/layers/slope.asc"));
  const GridMap elevation = ReadAsciiGrid(dir + "/layers/elevation.asc", "z");
  for (const float z : elevation.Layer("z")) EXPECT_NEAR(z, 87.5, 1e-4);
  EXPECT_NEAR(elevation.geometry().CornerWorld().x(), 612000.0, 1e-6);
}

}  // namespace
}  // namespace hylo::io
