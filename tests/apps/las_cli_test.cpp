// LAS survey maps through `hylo ground`, `hylo craft` and `hylo tile` end to end: a small site in
// UTM-sized coordinates (a sloping field with one building) written as LAS, and what each
// command writes back as LAS (world frame kept to 0.1 mm, classes, normals, tiles).
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <random>
#include <set>
#include <string>

#include "apps/cli_test_util.h"
#include "hylo/io/cloud_io.h"
#include "hylo/tiles/tiled_map.h"
#include "test_data.h"

namespace hylo {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;

const Eigen::Vector3d kUtm(512300.0, 5403100.0, 210.0);

// 40 x 40 m field rising 2 % along x, a point every 0.25 m, and a 6 x 6 m roof 4 m up in the
// middle; class 0 ("never classified"), intensity 100 on the ground and 200 on the roof.
io::CloudFile Site() {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.01);
  io::CloudFile site;
  for (double x = 0; x <= 40; x += 0.25) {
    for (double y = 0; y <= 40; y += 0.25) {
      const bool roof = std::abs(x - 20) <= 3 && std::abs(y - 20) <= 3;
      site.positions.push_back(kUtm +
                               Eigen::Vector3d(x, y, 0.02 * x + (roof ? 4.0 : 0.0) + noise(rng)));
      site.intensity.push_back(roof ? 200.f : 100.f);
      site.labels.push_back(0);
    }
  }
  return site;
}

class LasCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(testing::ScratchDir("las_cli"));
    io::WriteCloud(Path("site.las"), Site());
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string Path(const std::string& name) { return *dir_ + "/" + name; }
  static int Hylo(const std::string& args) {
    const int rc = testing::RunHylo(args, Path("log.txt"), Path("log.txt"));
    EXPECT_EQ(rc, 0) << args << "\n" << ReadText(Path("log.txt"));
    return rc;
  }
  static std::string* dir_;
};
std::string* LasCliTest::dir_ = nullptr;

TEST_F(LasCliTest, GroundWritesTheSplitAsAsprsClassesInTheWorldFrame) {
  ASSERT_EQ(Hylo("ground --in " + Path("site.las") + " --out-ground " + Path("ground.las") +
                 " --out-objects " + Path("objects.las")),
            0);
  const io::CloudFile ground = io::ReadCloud(Path("ground.las"));
  const io::CloudFile objects = io::ReadCloud(Path("objects.las"));
  const io::CloudFile site = io::ReadCloud(Path("site.las"));
  EXPECT_EQ(ground.positions.size() + objects.positions.size(), site.positions.size());
  EXPECT_GT(ground.positions.size(), 20000u);
  EXPECT_GE(objects.positions.size(), 500u);  // the roof
  EXPECT_EQ(ground.labels, std::vector<int32_t>(ground.positions.size(), 2));
  EXPECT_EQ(objects.labels, std::vector<int32_t>(objects.positions.size(), 1));
  for (std::size_t i = 0; i < objects.positions.size(); ++i) {
    EXPECT_EQ(objects.intensity[i], 200.f) << i;  // attributes travel with their points
    const Eigen::Vector3d local = objects.positions[i] - kUtm;
    EXPECT_GT(local.z(), 0.02 * local.x() + 3.5) << i;
  }
  // Points already on the 0.1 mm grid are written back exactly: every output point is an input
  // point, to the bit.
  std::set<std::array<double, 3>> input;
  for (const Eigen::Vector3d& p : site.positions) input.insert({p.x(), p.y(), p.z()});
  for (const io::CloudFile* out : {&ground, &objects}) {
    for (const Eigen::Vector3d& p : out->positions) {
      ASSERT_EQ(input.count({p.x(), p.y(), p.z()}), 1u) << p.transpose();
    }
  }
}

TEST_F(LasCliTest, CraftWritesNormalsAndLasTiles) {
  ASSERT_EQ(Hylo("craft --in " + Path("site.las") + " --out " + Path("crafted.las") +
                 " --voxel 0.2 --radius 0.6 --tiles " + Path("crafted_tiles") +
                 " --tile-format las --tile-size 20 --tile-voxel 0.1"),
            0);
  const io::CloudFile crafted = io::ReadCloud(Path("crafted.las"));
  ASSERT_GT(crafted.positions.size(), 1000u);
  ASSERT_EQ(crafted.normals.size(), crafted.positions.size());
  EXPECT_GT(crafted.positions.front().y(), 5.4e6);
  EXPECT_NEAR(crafted.normals.front().norm(), 1.f, 1e-3f);
  const tiles::TiledMapIndex index = tiles::ReadTiledMapIndex(Path("crafted_tiles"));
  tiles::CheckTiledMapFiles(Path("crafted_tiles"), index);
  for (const tiles::TiledMapTile& t : index.tiles) {
    EXPECT_EQ(fs::path(t.file).extension(), ".las");
    EXPECT_EQ(tiles::ReadTiledMapTile(Path("crafted_tiles"), index.origin_world, t).size(), t.points);
  }
}

TEST_F(LasCliTest, TileReadsALasMapAndWritesLasTiles) {
  ASSERT_EQ(Hylo("tile --in " + Path("site.las") + " --out " + Path("tiles") +
                 " --tile-size 20 --voxel 0.25 --tile-format LAS"),
            0);
  const tiles::TiledMapIndex index = tiles::ReadTiledMapIndex(Path("tiles"));
  EXPECT_EQ(index.origin_world, kUtm + Eigen::Vector3d(0.0, 0.0, -10.0));  // 100 m granularity
  EXPECT_EQ(index.tiles.size(), 9u);  // 40 m (and the edge at 40) in 20 m tiles: 3 x 3
  EXPECT_EQ(index.points, 161u * 161u);
  tiles::CheckTiledMapFiles(Path("tiles"), index);
  std::size_t points = 0;
  for (const tiles::TiledMapTile& t : index.tiles) {
    const PointCloud local = tiles::ReadTiledMapTile(Path("tiles"), index.origin_world, t);
    points += local.size();
    const io::CloudFile world = io::ReadCloud(Path("tiles") + "/" + t.file);
    EXPECT_NEAR(world.positions.front().x(), local.front().x() + index.origin_world.x(), 1e-3);
  }
  EXPECT_EQ(points, index.points);
  EXPECT_NE(testing::RunHylo(
                "tile --in " + Path("site.las") + " --out " + Path("t2") + " --tile-format laz",
                "/dev/null", "/dev/null"),
            0);
  EXPECT_FALSE(fs::exists(Path("t2")));
}

}  // namespace
}  // namespace hylo
