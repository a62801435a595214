// `hylo localize` on bad input: each case ends with exit code 1 and one line that names what
// is wrong, before any odometry is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "apps/cli_test_util.h"
#include "hylo/io/cloud_io.h"
#include "test_data.h"

namespace hylo {
namespace {

const std::string kConfig = std::string(HYLO_SOURCE_DIR) + "/config/presets/sim_vlp16.yaml";

using testing::ReadText;

class LocalizeCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::ScratchDir("localize_cli");
    io::CloudFile map;
    for (int i = 0; i < 1000; ++i) map.positions.emplace_back(0.1 * (i % 40), 0.1 * (i / 40), 0.0);
    io::WriteCloud(Path("map.pcd"), map);
    io::WriteCloud(Path("empty.pcd"), io::CloudFile());
  }
  std::string Path(const std::string& name) const { return dir_ + "/" + name; }
  // Runs `hylo localize` with `args`; returns the exit code, stderr in *error.
  int Localize(const std::string& args, std::string* error) {
    const std::string err = Path("stderr.txt");
    const int rc = testing::RunHylo(
        "localize --config " + kConfig + " --out " + Path("out") + " " + args, "/dev/null", err);
    *error = ReadText(err);
    return rc;
  }
  std::string dir_;
};

TEST_F(LocalizeCliTest, AMissingMapIsNamed) {
  std::string error;
  EXPECT_EQ(Localize("--log " + Path("none.bag") + " --map " + Path("absent.pcd") +
                         " --guess '0 0 0 0 0 0'",
                     &error),
            1);
  EXPECT_NE(error.find("absent.pcd"), std::string::npos) << error;
}

TEST_F(LocalizeCliTest, AnEmptyMapIsNamed) {
  std::string error;
  EXPECT_EQ(Localize("--log " + Path("none.bag") + " --map " + Path("empty.pcd") +
                         " --guess '0 0 0 0 0 0'",
                     &error),
            1);
  EXPECT_NE(error.find("empty.pcd"), std::string::npos) << error;
  EXPECT_NE(error.find("no point"), std::string::npos) << error;
}

TEST_F(LocalizeCliTest, AMissingGuessIsExplainedWhenGlobalLocalizationIsOff) {
  // Without a guess the whole map is searched, unless the configuration turns that off.
  const std::string config = Path("no_global.yaml");
  {
    std::ofstream out(config);
    out << ReadText(kConfig) << "\nlocalization:\n  global_enabled: false\n";
  }
  const std::string err = Path("stderr.txt");
  const int rc = testing::RunHylo("localize --config " + config + " --out " + Path("out") +
                                      " --log " + Path("none.bag") + " --map " + Path("map.pcd"),
                                  "/dev/null", err);
  const std::string error = ReadText(err);
  EXPECT_EQ(rc, 1);
  EXPECT_NE(error.find("--guess"), std::string::npos) << error;
  EXPECT_NE(error.find("global_enabled"), std::string::npos) << error;
}

TEST_F(LocalizeCliTest, WithoutAGuessOnlyTheLogIsStillNeeded) {
  // Global start: no guess is asked for; the missing log is the first problem named.
  std::string error;
  EXPECT_EQ(Localize("--log " + Path("none.bag") + " --map " + Path("map.pcd"), &error), 1);
  EXPECT_EQ(error.find("--guess"), std::string::npos) << error;
  EXPECT_NE(error.find("none.bag"), std::string::npos) << error;
}

TEST_F(LocalizeCliTest, AMalformedGuessNamesTheProblem) {
  std::string error;
  EXPECT_EQ(Localize("--log " + Path("none.bag") + " --map " + Path("map.pcd") +
                         " --guess '1 2 three 0 0 0'",
                     &error),
            1);
  EXPECT_NE(error.find("three"), std::string::npos) << error;
}

TEST_F(LocalizeCliTest, AMissingLogIsNamed) {
  std::string error;
  EXPECT_EQ(
      Localize("--log " + Path("none.bag") + " --map " + Path("map.pcd") + " --guess '0 0 0 0 0 0'",
               &error),
      1);
  EXPECT_NE(error.find("none.bag"), std::string::npos) << error;
  EXPECT_FALSE(std::filesystem::exists(Path("out/trajectory.tum")));
}

}  // namespace
}  // namespace hylo
