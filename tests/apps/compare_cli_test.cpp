// `hylo compare` end to end: every back-end on one short simulated session (SLAM), each in its
// own process and folder, one table in three forms; a log that cannot be read gives failed
// rows with the reason and a non-zero exit, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "apps/cli_test_util.h"
#include "hylo/io/json.h"
#include "test_data.h"

namespace hylo {
namespace {

namespace fs = std::filesystem;
const std::string kConfig = std::string(HYLO_SOURCE_DIR) + "/config/presets/sim_vlp16.yaml";

using testing::ReadText;
// Both streams into one log.
int RunHylo(const std::string& args, const std::string& log) {
  return testing::RunHylo(args, log, log);
}

TEST(CompareCliTest, EveryBackendOnOneSessionInOneTable) {
  const std::string dir = testing::ScratchDir("compare_cli");
  ASSERT_EQ(RunHylo("simulate --out " + dir +
                        "/sim --session a --duration 12 --column-deg 0.5 "
                        "--no-site",
                    dir + "/sim.txt"),
            0)
      << ReadText(dir + "/sim.txt");
  const int status = RunHylo("compare --log " + dir + "/sim/session_a.bag --config " + kConfig +
                                 " --gt " + dir + "/sim/session_a_truth.tum --out " + dir + "/cmp",
                             dir + "/cmp.txt");
  const std::string out = ReadText(dir + "/cmp.txt");
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("ATE RMSE [m]"), std::string::npos) << out;
  EXPECT_NE(ReadText(dir + "/cmp/comparison.md").find("| ieskf |"), std::string::npos);
  const io::Json json = io::ReadJsonFile(dir + "/cmp/comparison.json");
  const io::Json& rows = json.at("backends");
  ASSERT_EQ(rows.size(), 2u);
  for (const io::Json& row : rows) {
    const std::string backend = row.at("backend").get<std::string>();
    const std::string row_status = row.at("status").get<std::string>();
    if (row_status == "not available") continue;
    ASSERT_EQ(row_status, "ok") << backend << ": " << row.at("note").get<std::string>();
    EXPECT_TRUE(fs::exists(dir + "/cmp/" + backend + "/trajectory.tum")) << backend;
    // SLAM over ~10 m: a working back-end stays within decimetres (loose: a sanity bound).
    EXPECT_LT(io::NumberAt(row, "ate_rmse_m"), 0.2) << backend;
    EXPECT_LT(io::NumberAt(row, "ate_live_rmse_m"), 0.2) << backend;
    EXPECT_GT(io::NumberAt(row, "rpe_rmse_m"), 0.0) << backend;
    EXPECT_TRUE(std::isnan(io::NumberAt(row, "c2c_mean_m"))) << "no prior map: no c2c";
    // Own process: more than an empty process, far less than the whole machine.
    EXPECT_GT(io::NumberAt(row, "peak_memory_mb"), 5.0) << backend;
    EXPECT_LT(io::NumberAt(row, "peak_memory_mb"), 4000.0) << backend;
  }
}

TEST(CompareCliTest, UnreadableLogGivesFailedRowsAndNonZeroExit) {
  const std::string dir = testing::ScratchDir("compare_cli_bad");
  const int status = RunHylo(
      "compare --log " + dir + "/missing.bag --config " + kConfig + " --out " + dir + "/cmp",
      dir + "/cmp.txt");
  const std::string out = ReadText(dir + "/cmp.txt");
  EXPECT_NE(status, 0) << out;
  EXPECT_NE(out.find("missing.bag"), std::string::npos) << out;
  const io::Json json = io::ReadJsonFile(dir + "/cmp/comparison.json");
  for (const io::Json& row : json.at("backends")) {
    const std::string row_status = row.at("status").get<std::string>();
    EXPECT_TRUE(row_status == "failed" || row_status == "not available") << row_status;
    if (row_status == "failed") {
      EXPECT_NE(row.at("note").get<std::string>().find("missing.bag"), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace hylo
