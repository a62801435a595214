// Tiled maps: the index round trip and its errors, the tiles checked against the index, and
// the streaming tiler against the whole-map split (the same points, thinned the same way).

#include "hylo/tiles/tiled_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include "io/cloud_test_util.h"
#include "hylo/common/local_origin.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/json.h"
#include "hylo/tiles/map_tiler.h"
#include "hylo/tiles/tiles.h"
#include "hylo/registration/voxel_filter.h"
#include "test_data.h"

namespace hylo::tiles {
namespace {

namespace fs = std::filesystem;

TiledMapIndex SampleIndex() {
  TiledMapIndex index;
  index.tile_size_m = 25.0;
  index.voxel_m = 0.05;
  index.origin_world = Eigen::Vector3d(512300.0, 5403100.0, 200.0);
  index.source = "site.pcd";
  index.min_local = Eigen::Vector3f(-3.5f, 0.25f, -1.f);
  index.max_local = Eigen::Vector3f(40.125f, 24.5f, 7.75f);
  index.overview_file = "overview.pcd";
  index.overview_voxel_m = 0.5;
  index.overview_points = 12;
  for (int i = 0; i < 3; ++i) {
    TiledMapTile t;
    t.ix = i - 1;
    t.iy = 0;
    t.file = TileFileName(t.ix, t.iy);
    t.points = 100u + i;
    t.min_local = Eigen::Vector3f(25.f * t.ix + 0.1f, 0.25f, -1.f + 0.1f * i);
    t.max_local = Eigen::Vector3f(25.f * t.ix + 24.9f, 24.5f, 7.75f);
    index.tiles.push_back(t);
    index.points += t.points;
  }
  return index;
}

TEST(TiledMapIndex, RoundTripsEveryField) {
  const std::string dir = hylo::testing::ScratchDir("tiled_index");
  const TiledMapIndex index = SampleIndex();
  WriteTiledMapIndex(dir, index);
  EXPECT_TRUE(IsTiledMap(dir));
  EXPECT_FALSE(IsTiledMap(dir + "/index.json"));
  const TiledMapIndex read = ReadTiledMapIndex(dir);
  EXPECT_EQ(read.version, TiledMapIndex::kVersion);
  EXPECT_EQ(read.tile_size_m, index.tile_size_m);
  EXPECT_EQ(read.voxel_m, index.voxel_m);
  EXPECT_EQ(read.origin_world, index.origin_world);
  EXPECT_EQ(read.source, index.source);
  EXPECT_EQ(read.points, index.points);
  EXPECT_EQ(read.min_local, index.min_local);
  EXPECT_EQ(read.max_local, index.max_local);
  EXPECT_EQ(read.overview_file, index.overview_file);
  EXPECT_EQ(read.overview_voxel_m, index.overview_voxel_m);
  EXPECT_EQ(read.overview_points, index.overview_points);
  ASSERT_EQ(read.tiles.size(), index.tiles.size());
  for (std::size_t i = 0; i < index.tiles.size(); ++i) {
    EXPECT_EQ(read.tiles[i].ix, index.tiles[i].ix);
    EXPECT_EQ(read.tiles[i].iy, index.tiles[i].iy);
    EXPECT_EQ(read.tiles[i].file, index.tiles[i].file);
    EXPECT_EQ(read.tiles[i].points, index.tiles[i].points);
    EXPECT_EQ(read.tiles[i].min_local, index.tiles[i].min_local);  // floats survive JSON exactly
    EXPECT_EQ(read.tiles[i].max_local, index.tiles[i].max_local);
  }
}

// Writes `index` with one key replaced by `edit`, and expects the reader to name `fragment`.
void ExpectIndexError(const std::function<void(io::Json*)>& edit, const std::string& fragment) {
  const std::string dir = hylo::testing::ScratchDir("tiled_index_bad");
  WriteTiledMapIndex(dir, SampleIndex());
  io::Json json = io::ReadJsonFile(TiledMapIndexPath(dir));
  edit(&json);
  std::ofstream(TiledMapIndexPath(dir)) << io::DumpJson(json);
  try {
    ReadTiledMapIndex(dir);
    ADD_FAILURE() << "no error, expected " << fragment;
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("index.json"), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(TiledMapIndex, BadIndexesNameTheKey) {
  ExpectIndexError([](io::Json* j) { j->erase("tile_size_m"); }, "'tile_size_m'");
  ExpectIndexError([](io::Json* j) { (*j)["tiles"][1].erase("points"); }, "'tiles[1].points'");
  ExpectIndexError([](io::Json* j) { (*j)["tiles"][2]["min"] = "near"; }, "'tiles[2].min'");
  ExpectIndexError([](io::Json* j) { (*j)["version"] = 99; }, "version 99");
  ExpectIndexError([](io::Json* j) { (*j)["tiles"][1]["ix"] = (*j)["tiles"][0]["ix"]; },
                   "listed twice");
  ExpectIndexError([](io::Json* j) { (*j)["points"] = 7; }, "key 'points' says 7");
  ExpectIndexError([](io::Json* j) { (*j)["tiles"][0]["file"] = "../elsewhere.pcd"; },
                   "not a file inside the map directory");
  ExpectIndexError([](io::Json* j) { (*j)["format"] = "something else"; }, "'format'");
}

// A random map with UTM-sized coordinates: a ground sheet with bumps over 130 m x 90 m plus
// walls, some duplicate points, written as a binary_compressed PCD (read by field cursors).
io::CloudFile RandomMap(const Eigen::Vector3d& offset, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(-20.0, 110.0), y(-40.0, 50.0), u(0.0, 1.0);
  io::CloudFile map;
  for (int i = 0; i < 60000; ++i) {
    const double px = x(rng), py = y(rng);
    const double pz = 0.3 * std::sin(0.2 * px) + (u(rng) < 0.2 ? 5.0 * u(rng) : 0.0);
    map.positions.push_back(offset + Eigen::Vector3d(px, py, pz));
    if (i % 97 == 0) map.positions.push_back(map.positions.back());  // exact duplicates
  }
  return map;
}

TEST(MapTiler, StreamingTilerKeepsExactlyTheWholeMapThinnedAtOnce) {
  const std::string dir = hylo::testing::ScratchDir("map_tiler");
  const Eigen::Vector3d offset(512345.678, 5403210.123, 231.5);
  const io::CloudFile map = RandomMap(offset, 3);
  io::WriteCloud(dir + "/map.pcd", map, io::CloudEncoding::kBinaryCompressed);
  TileMapOptions options;
  options.tile_size_m = 25.0;
  options.voxel_m = 0.25;
  options.chunk_points = 4999;         // many chunks
  options.spill_buffer_points = 7001;  // many spill flushes
  const TileMapSummary summary = TileMapFile(dir + "/map.pcd", dir + "/tiled", options);
  EXPECT_EQ(summary.points_read, map.positions.size());

  // The whole-map reference: the prior map's origin rule and uniform sampling at once.
  const Eigen::Vector3d origin = ChooseOrigin(map.positions, options.origin_granularity_m);
  const PointCloud reference = registration::UniformSample(ToLocal(map.positions, origin),
                                                           static_cast<float>(options.voxel_m));
  const TiledMapIndex index = ReadTiledMapIndex(dir + "/tiled");
  EXPECT_EQ(index.origin_world, origin);
  EXPECT_EQ(index.points, reference.size());
  EXPECT_EQ(summary.points_written, reference.size());
  EXPECT_GT(index.tiles.size(), 10u);
  CheckTiledMapFiles(dir + "/tiled", index);
  const tiles::TileGrid grid(index.tile_size_m);
  PointCloud tiled;
  for (const TiledMapTile& t : index.tiles) {
    const PointCloud points = ReadTiledMapTile(dir + "/tiled", index.origin_world, t);
    for (const Eigen::Vector3f& p : points) {
      const tiles::TileKey key = grid.KeyOf(p, static_cast<float>(index.voxel_m));
      ASSERT_EQ(key.ix, t.ix);
      ASSERT_EQ(key.iy, t.iy);
    }
    tiled.insert(tiled.end(), points.begin(), points.end());
  }
  auto less = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  PointCloud expected = reference;
  std::sort(expected.begin(), expected.end(), less);
  std::sort(tiled.begin(), tiled.end(), less);
  EXPECT_EQ(tiled, expected);
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir + "/tiled")) {
    ++entries;
    EXPECT_TRUE(e.path().filename() == "index.json" || e.path().filename() == "tiles" ||
                e.path().filename() == "overview.pcd")
        << e.path();
  }
  EXPECT_EQ(entries, 3u);

  // The overview holds, for each of its voxels, the lowest map point in it.
  const PointCloud overview = ReadTiledMapOverview(dir + "/tiled", index);
  EXPECT_EQ(overview.size(), index.overview_points);
  ASSERT_FALSE(overview.empty());
  const PointCloud local = ToLocal(map.positions, origin);
  const float lowest = std::min_element(local.begin(), local.end(), [](auto& a, auto& b) {
                         return a.z() < b.z();
                       })->z();
  EXPECT_EQ(std::min_element(overview.begin(), overview.end(),
                             [](auto& a, auto& b) { return a.z() < b.z(); })
                ->z(),
            lowest);
}

// LAS tiles from a LAS map: world-frame files (survey software shows them in place) that read
// back, in the local frame, as the PCD tiles' points to within the LAS grid's half step.
TEST(MapTiler, LasTilesHoldTheWorldFrameAndReadBackLocal) {
  const std::string dir = hylo::testing::ScratchDir("map_tiler_las");
  const io::CloudFile map = RandomMap(Eigen::Vector3d(512345.678, 5403210.123, 231.5), 7);
  io::WriteCloud(dir + "/map.las", map);
  TileMapOptions options;
  options.tile_size_m = 25.0;
  options.voxel_m = 0.25;
  TileMapFile(dir + "/map.las", dir + "/pcd", options);
  options.tile_format = TileFormat::kLas;
  TileMapFile(dir + "/map.las", dir + "/las", options);
  const TiledMapIndex pcd = ReadTiledMapIndex(dir + "/pcd");
  const TiledMapIndex las = ReadTiledMapIndex(dir + "/las");
  CheckTiledMapFiles(dir + "/las", las);
  ASSERT_EQ(las.tiles.size(), pcd.tiles.size());
  EXPECT_EQ(las.origin_world, pcd.origin_world);
  for (std::size_t i = 0; i < las.tiles.size(); ++i) {
    const TiledMapTile& t = las.tiles[i];
    EXPECT_EQ(t.file, TileFileName(t.ix, t.iy, TileFormat::kLas));
    ASSERT_EQ(t.points, pcd.tiles[i].points);
    // The file is in the world frame ...
    const io::CloudFile file = io::ReadCloud(dir + "/las/" + t.file);
    EXPECT_GT(file.positions.front().y(), 5.4e6);
    // ... and the tile, read as the streamer reads it, is the PCD tile's points to 0.1 mm.
    const PointCloud a = ReadTiledMapTile(dir + "/las", las.origin_world, t);
    const PointCloud b = ReadTiledMapTile(dir + "/pcd", pcd.origin_world, pcd.tiles[i]);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      ASSERT_LE((a[k] - b[k]).cwiseAbs().maxCoeff(), 0.6e-4f) << t.file << " point " << k;
    }
  }
}

TEST(MapTiler, OutputIsCompleteOrAbsent) {
  const std::string dir = hylo::testing::ScratchDir("map_tiler_atomic");
  io::WriteCloud(dir + "/map.ply", RandomMap(Eigen::Vector3d::Zero(), 4));
  fs::create_directories(dir + "/busy");
  std::ofstream(dir + "/busy/notes.txt") << "not a map";
  TileMapOptions options;
  EXPECT_THROW(TileMapFile(dir + "/map.ply", dir + "/busy", options), std::runtime_error);
  EXPECT_TRUE(fs::exists(dir + "/busy/notes.txt"));
  // A failing input leaves nothing under the output's name, nor any partial directory.
  io::testing::Truncate(dir + "/map.ply", dir + "/cut.ply", io::testing::FileSize(dir + "/map.ply") / 2);
  EXPECT_THROW(TileMapFile(dir + "/cut.ply", dir + "/out", options), std::runtime_error);
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.is_directory() ? 1 : 0;
  EXPECT_EQ(entries, 1u);  // only busy/
  // A tiled map of the same name is replaced as a whole.
  options.tile_size_m = 100.0;
  TileMapFile(dir + "/map.ply", dir + "/out", options);
  options.tile_size_m = 20.0;
  TileMapFile(dir + "/map.ply", dir + "/out/", options);
  EXPECT_EQ(ReadTiledMapIndex(dir + "/out").tile_size_m, 20.0);
  for (const auto& e : fs::directory_iterator(dir + "/out/tiles")) {
    EXPECT_NO_THROW(io::ReadCloudInfo(e.path().string()));
  }
  // Invalid options are named.
  options.voxel_m = 0.3;  // 20 m is not a whole number of 0.3 m voxels
  EXPECT_THROW(TileMapFile(dir + "/map.ply", dir + "/out2", options), std::invalid_argument);
}

TEST(TiledMapFiles, TilesThatDoNotMatchTheIndexAreNamed) {
  const std::string dir = hylo::testing::ScratchDir("tiled_files");
  io::WriteCloud(dir + "/map.pcd", RandomMap(Eigen::Vector3d(1000.0, 2000.0, 0.0), 5));
  TileMapOptions options;
  TileMapFile(dir + "/map.pcd", dir + "/t", options);
  TiledMapIndex index = ReadTiledMapIndex(dir + "/t");
  ASSERT_GE(index.tiles.size(), 2u);
  const std::string first = dir + "/t/" + index.tiles[0].file;
  auto expect_error = [&](const std::function<void()>& f, const std::string& fragment) {
    try {
      f();
      ADD_FAILURE() << "no error, expected " << fragment;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  // A count that disagrees (header check and full read), bounds that disagree, a missing tile.
  index.tiles[0].points += 1;
  expect_error([&] { CheckTiledMapFiles(dir + "/t", index); }, "does not match its tiles");
  expect_error([&] { ReadTiledMapTile(dir + "/t", index.origin_world, index.tiles[0]); }, "does not match its tiles");
  index.tiles[0].points -= 1;
  index.tiles[0].max_local.z() += 1.f;
  expect_error([&] { ReadTiledMapTile(dir + "/t", index.origin_world, index.tiles[0]); }, "does not match its tiles");
  io::testing::Truncate(first, first + ".cut", io::testing::FileSize(first) - 8);
  fs::rename(first + ".cut", first);
  expect_error([&] { ReadTiledMapTile(dir + "/t", index.origin_world, index.tiles[0]); }, "truncated");
  fs::remove(first);
  expect_error([&] { CheckTiledMapFiles(dir + "/t", index); }, first + ": missing");
  expect_error([&] { ReadTiledMapTile(dir + "/t", index.origin_world, index.tiles[0]); }, "cannot open");
}

}  // namespace
}  // namespace hylo::tiles
