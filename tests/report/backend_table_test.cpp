// The per-back-end table: figures rounded as declared, "n/a" for what was not measured, rows
// of unavailable or failed back-ends kept (with their reason), columns aligned, JSON nulls.
#include "hylo/report/backend_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace hylo::report {
namespace {

BackendRow Ieskf() {
  BackendRow row;
  row.backend = "ieskf";
  row.c2c_mean_m = 0.031249;
  row.c2c_std_m = 0.02;
  row.ate_rmse_m = 0.0123456;
  row.ms_per_scan_median = 8.234;
  row.ms_per_scan_p99 = 13.876;
  row.peak_memory_mb = 151.26;
  row.scans = 240;
  return row;  // rpe_rmse_m left unmeasured
}

BackendRow FailedRun() {
  BackendRow row;
  row.backend = "sliding_window";
  row.status = RowStatus::kFailed;
  row.note = "session_b.bag: ICP initializer rejected the start";
  row.ate_rmse_m = 1.0;  // must not be shown for a row that is not ok
  return row;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(FormatFigureTest, RoundsAndMarksMissingValues) {
  EXPECT_EQ(FormatFigure(0.031249, 4), "0.0312");
  EXPECT_EQ(FormatFigure(0.03125001, 4), "0.0313");
  EXPECT_EQ(FormatFigure(13.876, 2), "13.88");
  EXPECT_EQ(FormatFigure(240.0, 0), "240");
  EXPECT_EQ(FormatFigure(std::nan(""), 3), "n/a");
  EXPECT_EQ(FormatFigure(INFINITY, 3), "n/a");
  EXPECT_EQ(FormatFigure(-0.5, 1), "-0.5");
}

TEST(FormatTableTest, MarkdownHasOneRowPerBackendAndTheNotes) {
  const std::vector<std::string> lines =
      Lines(FormatTable({Ieskf(), FailedRun()}, TableStyle::kMarkdown));
  ASSERT_GE(lines.size(), 6u);
  EXPECT_EQ(
      lines[0],
      "| back-end | c2c mean [m] | c2c std [m] | ATE RMSE [m] | live ATE [m] | RPE RMSE [m] | "
      "ms/scan median | ms/scan p99 | CPU ms/scan | peak mem [MiB] | scans |");
  EXPECT_EQ(lines[1], "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
  EXPECT_EQ(lines[2],
            "| ieskf | 0.0312 | 0.0200 | 0.0123 | n/a | n/a | 8.23 | 13.88 | n/a | 151.3 | 240 |");
  EXPECT_EQ(lines[3],
            "| sliding_window | failed | failed | failed | failed | failed | failed | failed | "
            "failed | failed | failed |");
  EXPECT_EQ(lines[4], "");
  EXPECT_EQ(lines[5],
            "- sliding_window (failed): session_b.bag: ICP initializer rejected the start");
}

TEST(FormatTableTest, TerminalColumnsLineUp) {
  const std::vector<std::string> lines =
      Lines(FormatTable({Ieskf(), FailedRun()}, TableStyle::kTerminal));
  ASSERT_GE(lines.size(), 5u);
  // Header, rule and both rows have the same width; the rule spans it.
  EXPECT_EQ(lines[0].size(), lines[1].size());
  EXPECT_EQ(lines[0].size(), lines[2].size());
  EXPECT_EQ(lines[0].size(), lines[3].size());
  EXPECT_EQ(lines[1].find_first_not_of('-'), std::string::npos);
  // Right-aligned figures: the ATE header and its value end in the same column.
  const std::size_t ate_end = lines[0].find("ATE RMSE [m]") + std::string("ATE RMSE [m]").size();
  EXPECT_EQ(lines[2].find("0.0123") + 6, ate_end);
  EXPECT_EQ(lines[2].rfind("ieskf", 0), 0u);
  EXPECT_NE(lines[4].find("ICP initializer rejected the start"), std::string::npos);
}

TEST(TableToJsonTest, FiguresUnderUnitKeysAndNullWhenMissing) {
  const io::Json json = TableToJson({Ieskf(), FailedRun()});
  ASSERT_TRUE(json.is_array());
  ASSERT_EQ(json.size(), 2u);
  const io::Json& ieskf = json.at(0);
  EXPECT_EQ(ieskf.at("backend"), "ieskf");
  EXPECT_EQ(ieskf.at("status"), "ok");
  EXPECT_DOUBLE_EQ(ieskf.at("ate_rmse_m").get<double>(), 0.0123456);
  EXPECT_DOUBLE_EQ(ieskf.at("peak_memory_mb").get<double>(), 151.26);
  EXPECT_TRUE(ieskf.at("rpe_rmse_m").is_null());
  const io::Json& sw = json.at(1);
  EXPECT_EQ(sw.at("status"), "failed");
  EXPECT_EQ(sw.at("note"), "session_b.bag: ICP initializer rejected the start");
}

TEST(FormatTableTest, EmptyTableStillHasItsHeader) {
  const std::vector<std::string> lines = Lines(FormatTable({}, TableStyle::kMarkdown));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find("ATE RMSE"), std::string::npos);
}

}  // namespace
}  // namespace hylo::report
