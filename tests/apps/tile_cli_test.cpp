// `hylo tile` end to end, and `hylo localize --map DIR` on tiled maps that are broken: each
// case ends with exit code 1 and one line naming the file and what is wrong, before any
// odometry is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "apps/cli_test_util.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/json.h"
#include "hylo/tiles/tiled_map.h"
#include "test_data.h"

namespace hylo {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;

const std::string kConfig = std::string(HYLO_SOURCE_DIR) + "/config/presets/sim_vlp16.yaml";

class TileCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::ScratchDir("tile_cli");
    io::CloudFile map;  // 120 m x 60 m of ground in UTM-sized coordinates, every 0.5 m
    for (int i = 0; i < 240; ++i) {
      for (int j = 0; j < 120; ++j) {
        map.positions.emplace_back(600000.0 + 0.5 * i, 5200000.0 + 0.5 * j, 0.01 * (i % 7));
      }
    }
    io::WriteCloud(Path("map.pcd"), map, io::CloudEncoding::kBinaryCompressed);
  }
  std::string Path(const std::string& name) const { return dir_ + "/" + name; }
  int Hylo(const std::string& args, std::string* error) {
    const std::string err = Path("stderr.txt");
    const int rc = testing::RunHylo(args, Path("stdout.txt"), err);
    *error = ReadText(err);
    return rc;
  }
  int Localize(const std::string& map, std::string* error) {
    return Hylo("localize --config " + kConfig + " --out " + Path("out") + " --log " +
                    Path("none.bag") + " --map " + map + " --guess '600030 5200030 0 0 0 0'",
                error);
  }
  std::string dir_;
};

TEST_F(TileCliTest, TilesAMapAndSaysHowFastAndHowBig) {
  std::string error;
  ASSERT_EQ(Hylo("tile --in " + Path("map.pcd") + " --out " + Path("tiles") +
                     " --tile-size 20 --voxel 0.5 --json " + Path("tile.json"),
                 &error),
            0)
      << error;
  const tiles::TiledMapIndex index = tiles::ReadTiledMapIndex(Path("tiles"));
  EXPECT_EQ(index.points, 240u * 120u);
  EXPECT_EQ(index.tiles.size(), 6u * 3u);
  EXPECT_EQ(index.origin_world, Eigen::Vector3d(600000.0, 5200000.0, 0.0));
  tiles::CheckTiledMapFiles(Path("tiles"), index);
  const io::Json summary = io::ReadJsonFile(Path("tile.json"));
  EXPECT_EQ(io::NumberAt(summary, "points_read"), 240.0 * 120.0);
  EXPECT_GT(io::NumberAt(summary, "points_per_s"), 0.0);
  EXPECT_GT(io::NumberAt(summary, "peak_memory_mb"), 0.0);
  // A tile size that is not a whole number of voxels is refused, naming the option.
  EXPECT_EQ(
      Hylo("tile --in " + Path("map.pcd") + " --out " + Path("t2") + " --tile-size 20 --voxel 0.3",
           &error),
      1);
  EXPECT_NE(error.find("tile_size_m"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(Path("t2")));
}

TEST_F(TileCliTest, BrokenTiledMapsAreNamedBeforeAnyOdometry) {
  std::string error;
  ASSERT_EQ(
      Hylo("tile --in " + Path("map.pcd") + " --out " + Path("tiles") + " --tile-size 20", &error),
      0)
      << error;
  const tiles::TiledMapIndex index = tiles::ReadTiledMapIndex(Path("tiles"));
  auto broken_copy = [&](const std::string& name) {
    fs::copy(Path("tiles"), Path(name), fs::copy_options::recursive);
    return Path(name);
  };
  // A tile that is gone.
  const std::string missing = broken_copy("missing");
  fs::remove(missing + "/" + index.tiles[3].file);
  EXPECT_EQ(Localize(missing, &error), 1);
  EXPECT_NE(error.find(index.tiles[3].file + ": missing"), std::string::npos) << error;
  // An index whose count disagrees with its tile.
  const std::string counts = broken_copy("counts");
  tiles::TiledMapIndex edited = index;
  edited.tiles[2].points += 5;
  edited.points += 5;
  tiles::WriteTiledMapIndex(counts, edited);
  EXPECT_EQ(Localize(counts, &error), 1);
  EXPECT_NE(error.find(index.tiles[2].file), std::string::npos) << error;
  EXPECT_NE(error.find("does not match its tiles"), std::string::npos) << error;
  // A tile whose body is cut short (its header is fine): found when it loads, at the start.
  const std::string cut = broken_copy("cut");
  for (const tiles::TiledMapTile& t : index.tiles) {
    if (t.ix != 1 || t.iy != 1) continue;  // the tile of the guess: local (30, 30) m
    const std::string file = cut + "/" + t.file;
    fs::resize_file(file, fs::file_size(file) - 100);
    EXPECT_EQ(Localize(cut, &error), 1);
    EXPECT_NE(error.find(t.file), std::string::npos) << error;
    EXPECT_NE(error.find("truncated"), std::string::npos) << error;
  }
  // A directory that is not a tiled map.
  fs::create_directories(Path("empty"));
  EXPECT_EQ(Localize(Path("empty"), &error), 1);
  EXPECT_NE(error.find("index.json"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(Path("out/trajectory.tum")));
}

}  // namespace
}  // namespace hylo
