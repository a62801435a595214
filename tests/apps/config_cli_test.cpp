// `hylo config` end to end: the built executable prints the reference the committed doc holds,
// defaults that load back, and checks files with the reader's own errors.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "cli_test_util.h"
#include "hylo/config/config_doc.h"
#include "hylo/config/run_config.h"
#include "test_data.h"

namespace hylo {
namespace {

using testing::ReadText;
using testing::RunHylo;

class ConfigCliTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::ScratchDir("config_cli"); }
  std::string Path(const std::string& name) const { return dir_ + "/" + name; }
  std::string dir_;
};

// The command the doc test names is the one that writes docs/configuration.md.
TEST_F(ConfigCliTest, DocIsTheReference) {
  ASSERT_EQ(RunHylo("config --doc --out " + Path("configuration.md"), Path("log"), Path("log")), 0)
      << ReadText(Path("log"));
  EXPECT_EQ(ReadText(Path("configuration.md")), config::ConfigurationReference());
  ASSERT_EQ(RunHylo("config --doc", Path("stdout.md"), Path("log")), 0) << ReadText(Path("log"));
  EXPECT_EQ(ReadText(Path("stdout.md")), config::ConfigurationReference());
}

TEST_F(ConfigCliTest, DefaultsLoadBackAsTheDefaults) {
  ASSERT_EQ(RunHylo("config --defaults", Path("defaults.yaml"), Path("log")), 0)
      << ReadText(Path("log"));
  const config::RunConfig loaded = config::LoadRunConfig(Path("defaults.yaml"));
  EXPECT_EQ(config::ToYaml(loaded), config::ToYaml(config::RunConfig()));
}

TEST_F(ConfigCliTest, CheckAcceptsAPresetAndNamesWhatIsWrong) {
  const std::string preset = std::string(HYLO_SOURCE_DIR) + "/config/presets/vlp16.yaml";
  ASSERT_EQ(RunHylo("config --check " + preset + " --out " + Path("effective.yaml"), Path("log"),
                    Path("log")),
            0)
      << ReadText(Path("log"));
  EXPECT_NE(ReadText(Path("log")).find("valid"), std::string::npos) << ReadText(Path("log"));
  EXPECT_EQ(config::LoadRunConfig(Path("effective.yaml")).lidar.topic, "/velodyne_points");

  std::ofstream(Path("twice.yaml")) << "imu:\n  rate_hz: 200\n  rate_hz: 400\n";
  EXPECT_EQ(RunHylo("config --check " + Path("twice.yaml"), Path("log"), Path("log")), 1);
  const std::string error = ReadText(Path("log"));
  EXPECT_NE(error.find("twice.yaml: imu.rate_hz: the key is given twice (line 2 and line 3)"),
            std::string::npos)
      << error;
  EXPECT_NE(RunHylo("config", Path("log"), Path("log")), 0) << "one of the three is required";
}

}  // namespace
}  // namespace hylo
