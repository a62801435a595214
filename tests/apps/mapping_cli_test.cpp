// `hylo craft`, `hylo ground` and `hylo traversability` end to end: the built executable on a
// small synthetic site written here (a gently sloping field with one building), checking what
// each command writes (clouds, costmap files, JSON summary) and how it refuses bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>

#include "apps/cli_test_util.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/json.h"
#include "test_data.h"

namespace hylo {
namespace {

using testing::ReadText;

int RunHylo(const std::string& args, const std::string& log_path) {
  return testing::RunHylo(args, log_path, log_path);
}

// 40 x 40 m field rising 2 % along x, a point every 0.25 m with 1 cm noise, and a 6 x 6 m
// building 4 m high (roof and walls) in the middle; the building's points have z > 3 m above
// the field under them.
constexpr double kRoofHeightM = 4.0;
double FieldHeight(double x) { return 0.02 * x; }
bool InBuilding(double x, double y) { return std::abs(x - 20) <= 3 && std::abs(y - 20) <= 3; }

io::CloudFile SyntheticSite() {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  io::CloudFile site;
  for (double x = 0; x <= 40; x += 0.25) {
    for (double y = 0; y <= 40; y += 0.25) {
      const double z = FieldHeight(x) + (InBuilding(x, y) ? kRoofHeightM : 0.0);
      site.positions.emplace_back(x, y, z + noise(rng));
    }
  }
  for (double s = -3; s <= 3; s += 0.25) {  // walls, every 0.25 m up to the roof
    for (double h = 0.25; h < kRoofHeightM; h += 0.25) {
      for (const Eigen::Vector2d& xy : {Eigen::Vector2d(17, 20 + s), Eigen::Vector2d(23, 20 + s),
                                        Eigen::Vector2d(20 + s, 17), Eigen::Vector2d(20 + s, 23)}) {
        site.positions.emplace_back(xy.x(), xy.y(), FieldHeight(xy.x()) + h);
      }
    }
  }
  return site;
}

class MappingCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(testing::ScratchDir("mapping_cli"));
    io::WriteCloud(Path("site.pcd"), SyntheticSite(), io::CloudEncoding::kBinary);
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string Path(const std::string& name) { return *dir_ + "/" + name; }

  // Runs `hylo ground` on the site with `extra` options; expects success and a clean split:
  // no ground point higher above the field than `max_ground_m` (the back-end's threshold on
  // this 2 % field, plus noise).
  static void ExpectBuildingSplitOff(const std::string& extra, const std::string& tag,
                                     double max_ground_m) {
    const std::string ground = Path(tag + "_ground.pcd"), objects = Path(tag + "_objects.pcd");
    ASSERT_EQ(RunHylo("ground --in " + Path("site.pcd") + " --out-ground " + ground +
                          " --out-objects " + objects + " --json " + Path(tag + ".json") + " " +
                          extra,
                      Path(tag + ".log")),
              0)
        << ReadText(Path(tag + ".log"));
    const io::CloudFile g = io::ReadCloud(ground), o = io::ReadCloud(objects);
    const io::Json json = io::ReadJsonFile(Path(tag + ".json"));
    EXPECT_EQ(io::NumberAt(json, "points.ground"), double(g.positions.size()));
    EXPECT_EQ(io::NumberAt(json, "points.objects"), double(o.positions.size()));
    // No roof, no wall above its foot; and nearly every field point is ground.
    std::size_t high_in_ground = 0, field_in_ground = 0, field_points = 0;
    for (const Eigen::Vector3d& p : g.positions) {
      const double above_field_m = p.z() - FieldHeight(p.x());
      high_in_ground += above_field_m > max_ground_m;
      field_in_ground += above_field_m < 0.1;
    }
    for (const Eigen::Vector3d& p : SyntheticSite().positions) {
      field_points += p.z() - FieldHeight(p.x()) < 0.1 && !InBuilding(p.x(), p.y());
    }
    EXPECT_EQ(high_in_ground, 0u) << tag;
    EXPECT_GE(field_in_ground, 0.99 * field_points) << tag;
    EXPECT_GT(o.positions.size(), 25u * 25u) << tag;  // at least the roof
  }

  static std::string* dir_;
};
std::string* MappingCliTest::dir_ = nullptr;

// SMRF by default, the cloth filter on request (0.5 m from the cloth), and its other hole
// fill; the summary names the method and its options. SMRF's DEM stands on the lowest return
// of each cell, and along this building's edge that is the wall's first return, 0.25 m up:
// wall returns up to 0.25 m + the elevation threshold (0.7 m by default, 0.15 m for robot
// maps) + 1.25 x the DEM's slope at that step (up to 0.16 m) are ground, the rest of the
// 4 m building is not.
TEST_F(MappingCliTest, GroundSplitsTheBuildingOffWithEitherBackEnd) {
  ExpectBuildingSplitOff("", "defaults", 1.2);
  const std::string defaults = ReadText(Path("defaults.json"));
  EXPECT_NE(defaults.find("\"method\": \"smrf\""), std::string::npos) << defaults;
  EXPECT_NE(defaults.find("\"max_window_m\": 24"), std::string::npos) << defaults;
  ExpectBuildingSplitOff("--smrf-threshold 0.15", "robot_map", 0.6);
  ExpectBuildingSplitOff("--method csf", "csf", 0.55);
  ExpectBuildingSplitOff("--method csf --resolution 1 --rigidness 3 --hole-fill mean", "paper",
                         0.55);
  const std::string paper = ReadText(Path("paper.json"));
  EXPECT_NE(paper.find("\"method\": \"csf\""), std::string::npos) << paper;
  EXPECT_NE(paper.find("\"hole_fill\": \"mean\""), std::string::npos) << paper;
  EXPECT_NE(paper.find("\"damping\""), std::string::npos) << "every option, from the field list";
}

TEST_F(MappingCliTest, CraftThenTraversabilityWriteTheirFiles) {
  ExpectBuildingSplitOff("", "chain", 1.2);
  ASSERT_EQ(RunHylo("craft --in " + Path("chain_ground.pcd") + " --out " +
                        Path("chain_clean.ply") + " --voxel 0.2 --radius 0.6 --json " +
                        Path("craft.json"),
                    Path("craft.log")),
            0)
      << ReadText(Path("craft.log"));
  const io::CloudFile clean = io::ReadCloud(Path("chain_clean.ply"));
  EXPECT_GT(clean.positions.size(), 10000u);
  EXPECT_EQ(clean.normals.size(), clean.positions.size());
  EXPECT_EQ(io::NumberAt(io::ReadJsonFile(Path("craft.json")), "points.output"),
            double(clean.positions.size()));

  const std::string out = Path("costmap");
  ASSERT_EQ(RunHylo("traversability --ground " + Path("chain_clean.ply") + " --objects " +
                        Path("chain_objects.pcd") + " --out " + out + " --resolution 0.5 --json " +
                        Path("trav.json"),
                    Path("trav.log")),
            0)
      << ReadText(Path("trav.log"));
  for (const char* file : {"costmap.pgm", "costmap.yaml", "costmap.png"}) {
    EXPECT_TRUE(std::filesystem::exists(out + "/" + file)) << file;
  }
  const std::string yaml = ReadText(out + "/costmap.yaml");
  EXPECT_NE(yaml.find("resolution: 0.5"), std::string::npos) << yaml;
  // The building's cells are lethal.
  EXPECT_GT(io::NumberAt(io::ReadJsonFile(Path("trav.json")), "cells.lethal"), 0.0);
}

TEST_F(MappingCliTest, BadInputIsRefusedWithTheReason) {
  const std::string log = Path("bad.log");
  EXPECT_NE(RunHylo("ground --in " + Path("site.pcd") + " --out-ground " + Path("x.pcd") +
                        " --out-objects " + Path("y.pcd") + " --hole-fill sideways",
                    log),
            0);
  EXPECT_NE(ReadText(log).find("hole-fill"), std::string::npos) << ReadText(log);
  EXPECT_FALSE(std::filesystem::exists(Path("x.pcd")));

  EXPECT_NE(RunHylo("ground --in " + Path("site.pcd") + " --out-ground " + Path("x.pcd") +
                        " --out-objects " + Path("y.pcd") + " --method csf --rigidness 0",
                    log),
            0);
  EXPECT_NE(ReadText(log).find("rigidness"), std::string::npos) << ReadText(log);
  EXPECT_NE(RunHylo("ground --in " + Path("site.pcd") + " --out-ground " + Path("x.pcd") +
                        " --out-objects " + Path("y.pcd") + " --smrf-cell 0",
                    log),
            0);
  EXPECT_NE(ReadText(log).find("cell_m"), std::string::npos) << ReadText(log);
  EXPECT_NE(RunHylo("ground --in " + Path("site.pcd") + " --out-ground " + Path("x.pcd") +
                        " --out-objects " + Path("y.pcd") + " --method pmf",
                    log),
            0);
  EXPECT_NE(ReadText(log).find("method"), std::string::npos) << ReadText(log);

  const std::string missing = Path("no_such_cloud.pcd");
  for (const std::string& command :
       {"craft --in " + missing + " --out " + Path("x.ply"),
        "ground --in " + missing + " --out-ground " + Path("x.pcd") + " --out-objects " +
            Path("y.pcd"),
        "traversability --ground " + missing + " --out " + Path("nowhere")}) {
    EXPECT_NE(RunHylo(command, log), 0) << command;
    EXPECT_NE(ReadText(log).find("no_such_cloud.pcd"), std::string::npos)
        << command << ": " << ReadText(log);
  }
}

}  // namespace
}  // namespace hylo
