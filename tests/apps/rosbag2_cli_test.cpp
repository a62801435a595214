// ROS 2 recordings through the `hylo` command line: the same simulated session written as a
// ROS1 bag, a rosbag2 directory with sqlite3 storage, with MCAP storage and with zstd MCAP
// chunks (`hylo simulate --format`), and converted to lz4 MCAP (`hylo convert`), gives the same
// trajectory.tum, byte for byte, through `hylo map`; `hylo info` describes each.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "apps/cli_test_util.h"
#include "hylo/io/json.h"
#include "test_data.h"

namespace hylo {
namespace {

using testing::ReadText;

const std::string kConfig = std::string(HYLO_SOURCE_DIR) + "/config/presets/sim_vlp16.yaml";

class Rosbag2Cli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { dir_ = new std::string(testing::ScratchDir("rosbag2_cli")); }
  static void TearDownTestSuite() { delete dir_; }
  static std::string Path(const std::string& name) { return *dir_ + "/" + name; }

  static int Run(const std::string& args, const std::string& log) {
    return testing::RunHylo(args, Path(log), Path(log));
  }

  /// The 8 s session in `format`; returns the log's path.
  static std::string Simulate(const std::string& format) {
    const std::string out = Path("sim_" + format);
    EXPECT_EQ(Run("simulate --out " + out + " --session a --duration 8 --column-deg 1 --no-site " +
                      "--format " + format,
                  "simulate_" + format + ".log"),
              0)
        << ReadText(Path("simulate_" + format + ".log"));
    return out + (format == "ros1" ? "/session_a.bag" : "/session_a");
  }

  /// `hylo map` on `log`; returns trajectory.tum's bytes.
  static std::string Trajectory(const std::string& log, const std::string& tag) {
    const std::string out = Path("map_" + tag);
    EXPECT_EQ(
        Run("map --log " + log + " --config " + kConfig + " --out " + out, "map_" + tag + ".log"),
        0)
        << ReadText(Path("map_" + tag + ".log"));
    return ReadText(out + "/trajectory.tum");
  }

  static std::string* dir_;
};
std::string* Rosbag2Cli::dir_ = nullptr;

TEST_F(Rosbag2Cli, TheSameSessionInEveryFormatGivesBitIdenticalTrajectories) {
  const std::string reference = Trajectory(Simulate("ros1"), "ros1");
  ASSERT_GT(reference.size(), 1000u);
  for (const std::string format : {"sqlite3", "mcap", "mcap-zstd"}) {
    const std::string log = Simulate(format);
    EXPECT_EQ(Trajectory(log, format), reference) << format;
    ASSERT_EQ(Run("info " + log + " --json " + Path(format + ".json"), "info_" + format + ".log"),
              0)
        << ReadText(Path("info_" + format + ".log"));
    const io::Json info = io::ReadJsonFile(Path(format + ".json"));
    EXPECT_EQ(info["kind"], "rosbag2");
    EXPECT_EQ(info["storage"], format == "sqlite3" ? "sqlite3" : "mcap");
    EXPECT_EQ(info["compression"], format == "mcap-zstd" ? "zstd" : "none");
    EXPECT_EQ(info["topics"][1]["name"], "/points");
    EXPECT_EQ(info["topics"][1]["time_convention"], "velodyne");
    EXPECT_EQ(info["topics"][0]["message_count"], 1601);
  }
  // A ROS1 bag converted to a single lz4 MCAP file maps to the same trajectory too.
  const std::string converted = Path("converted.mcap");
  ASSERT_EQ(Run("convert --in " + Path("sim_ros1/session_a.bag") + " --out " + converted +
                    " --format mcap-lz4",
                "convert.log"),
            0)
      << ReadText(Path("convert.log"));
  EXPECT_NE(ReadText(Path("convert.log")).find("80 scans (velodyne layout), 1601 IMU samples"),
            std::string::npos)
      << ReadText(Path("convert.log"));
  EXPECT_EQ(Trajectory(converted, "converted"), reference);
  // convert never writes over a log.
  EXPECT_EQ(Run("convert --in " + Path("sim_ros1/session_a.bag") + " --out " + converted,
                "convert_again.log"),
            1);
  EXPECT_NE(ReadText(Path("convert_again.log")).find("exists"), std::string::npos);
}

}  // namespace
}  // namespace hylo
