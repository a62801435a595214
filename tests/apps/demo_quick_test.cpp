// `hylo demo --quick` end to end: the built executable runs the whole pipeline on the
// simulated site once (about a minute); the figures of its summary.json must be within
// bounds, and the report, plots and costmap image must exist as real PNGs. One test, so that
// ctest (one process per test) runs the demo once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "apps/cli_test_util.h"
#include "hylo/io/json.h"
#include "hylo/report/gnuplot.h"
#include "test_data.h"

namespace hylo {
namespace {

namespace fs = std::filesystem;

using testing::ReadText;

const io::Json* BackendRow(const io::Json& summary, const std::string& backend) {
  for (const io::Json& row : summary.at("localization_b").at("backends")) {
    if (row.at("backend") == backend) return &row;
  }
  return nullptr;
}

std::string Text(const io::Json& row, const char* key) {
  const auto value = row.find(key);
  return value != row.end() && value->is_string() ? value->get<std::string>() : "";
}

// The IESKF must reach the bounds; every other back-end has a row, and when it is built it
// meets the same bounds (NaN, a missing figure, fails the comparisons too).
void CheckLocalization(const io::Json& summary) {
  for (const std::string backend : {"ieskf", "sliding_window"}) {
    SCOPED_TRACE(backend);
    const io::Json* row = BackendRow(summary, backend);
    ASSERT_NE(row, nullptr);
    if (backend != "ieskf" && Text(*row, "status") == "not available") continue;
    ASSERT_EQ(Text(*row, "status"), "ok") << Text(*row, "note");
    EXPECT_LE(io::NumberAt(*row, "ate_rmse_m"), 0.05);
    EXPECT_LE(io::NumberAt(*row, "c2c_mean_m"), 0.10);
    EXPECT_GT(io::NumberAt(*row, "c2c_mean_m"), 0.0);
    EXPECT_GT(io::NumberAt(*row, "ms_per_scan_median"), 0.0);
    EXPECT_GE(io::NumberAt(*row, "ms_per_scan_p99"), io::NumberAt(*row, "ms_per_scan_median"));
    EXPECT_GT(io::NumberAt(*row, "peak_memory_mb"), 1.0);
    EXPECT_GT(io::NumberAt(*row, "scans"), 200.0);  // B: 30 s at 10 Hz, less the start
  }
}

void CheckReportAndImages(const std::string& run) {
  const std::string md = ReadText(run + "/report.md");
  EXPECT_NE(md.find("| ieskf |"), std::string::npos);
  EXPECT_NE(md.find("| sliding_window |"), std::string::npos);
  EXPECT_NE(md.find("![costmap](costmap/costmap.png)"), std::string::npos);
  EXPECT_TRUE(report::IsPngFile(run + "/costmap/costmap.png"));
  if (std::system("gnuplot --version > /dev/null 2>&1") != 0) {
    EXPECT_NE(md.find("Plot missing"), std::string::npos);  // and the report says why
    GTEST_SKIP() << "gnuplot not installed: the plots are reported missing";
  }
  for (const std::string png : {"plots/top_view.png", "plots/error_over_time.png"}) {
    EXPECT_TRUE(report::IsPngFile(run + "/" + png)) << png;
    EXPECT_GT(fs::file_size(run + "/" + png), 5000u) << png;
    EXPECT_NE(md.find("](" + png + ")"), std::string::npos) << png;
  }
}

// The inspection step: session A's equipment planned on the crafted map. Most targets lie in
// the mapped yard and must be planned; the route returns to its start; the files of `hylo
// inspect` are there, one plan.csv row per target.
void CheckInspection(const io::Json& summary, const std::string& run) {
  const double total = io::NumberAt(summary, "inspection.plan_targets.total");
  const double planned = io::NumberAt(summary, "inspection.plan_targets.planned");
  EXPECT_GE(total, 30.0);
  EXPECT_GE(planned, 0.8 * total);
  EXPECT_EQ(planned + io::NumberAt(summary, "inspection.plan_targets.occluded") +
                io::NumberAt(summary, "inspection.plan_targets.unreachable"),
            total);
  EXPECT_EQ(summary.at("inspection").at("not_planned").size(), total - planned);
  EXPECT_GT(io::NumberAt(summary, "inspection.plan_route.length_m"), 100.0);
  EXPECT_LT(io::NumberAt(summary, "inspection.seconds"), 30.0);
  const std::string plan_csv = ReadText(run + "/inspection/plan.csv");
  EXPECT_EQ(static_cast<double>(std::count(plan_csv.begin(), plan_csv.end(), '\n')), total + 1);
  EXPECT_NE(plan_csv.find("transformer_1_tank,planned,"), std::string::npos) << plan_csv;
  EXPECT_TRUE(report::IsPngFile(run + "/inspection/plan.png"));
  EXPECT_TRUE(fs::exists(run + "/inspection/route.csv"));
  EXPECT_NE(ReadText(run + "/report.md").find("![Inspection plan](inspection/plan.png)"),
            std::string::npos);
}

TEST(DemoQuickTest, FiguresWithinBoundsReportAndImagesWritten) {
  const std::string out = testing::ScratchDir("demo_quick");
  const int status =
      testing::RunHylo("demo --quick --out " + out, out + "/log.txt", out + "/log.txt");
  const std::string log = ReadText(out + "/log.txt");
  ASSERT_EQ(status, 0) << log;
  // It ends with the table and the report's path.
  EXPECT_NE(log.find("ATE RMSE [m]"), std::string::npos) << log;
  EXPECT_NE(log.find("report:  " + out), std::string::npos) << log;
  const std::string run = out + "/latest";
  ASSERT_TRUE(fs::is_symlink(run));
  const io::Json summary = io::ReadJsonFile(run + "/summary.json");
  EXPECT_LE(io::NumberAt(summary, "slam_a.ate_rmse_m"), 0.05);
  EXPECT_GT(io::NumberAt(summary, "traversability.cells.free"), 100.0);
  EXPECT_GT(io::NumberAt(summary, "traversability.cells.lethal"), 100.0);
  CheckLocalization(summary);
  CheckInspection(summary, run);
  CheckReportAndImages(run);
}

}  // namespace
}  // namespace hylo
