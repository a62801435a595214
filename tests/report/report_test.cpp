// report.md: the table, figures linked relative to the report, a missing plot explained in
// place of its image, parameters and files listed.
#include "hylo/report/report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_data.h"

namespace hylo::report {
namespace {

TEST(ReportTest, MarkdownHoldsTableFiguresCostmapParametersAndFiles) {
  const std::string dir = testing::ScratchDir("report_md");
  std::filesystem::create_directories(dir + "/plots");
  std::ofstream(dir + "/costmap.png") << "x";
  ReportContent c;
  c.title = "hylo demo";
  c.summary = "Two sessions.";
  BackendRow row;
  row.backend = "ieskf";
  row.ate_rmse_m = 0.02;
  c.rows = {row};
  c.plots.push_back({"Top view", dir + "/plots/top view.png", true, ""});
  c.plots.push_back({"Error over time", dir + "/plots/error.png", false, "gnuplot not found"});
  c.costmap_png = dir + "/costmap.png";
  c.parameters = {{"guess error", "1.0 m, 10 deg"}};
  c.files = {{"summary", dir + "/summary.json"}, {"elsewhere", "/var/data/x.pcd"}};
  WriteReport(dir + "/report.md", c);
  std::ifstream in(dir + "/report.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string md = ss.str();
  EXPECT_EQ(md.rfind("# hylo demo\n\nTwo sessions.\n", 0), 0u);
  EXPECT_NE(md.find("| ieskf | n/a | n/a | 0.0200 |"), std::string::npos) << md;
  EXPECT_NE(md.find("![Top view](<plots/top view.png>)"), std::string::npos) << md;
  EXPECT_NE(md.find("*Plot missing (`plots/error.png`): gnuplot not found*"), std::string::npos)
      << md;
  EXPECT_EQ(md.find("![Error over time]"), std::string::npos);
  EXPECT_NE(md.find("![costmap](costmap.png)"), std::string::npos) << md;
  EXPECT_NE(md.find("| guess error | 1.0 m, 10 deg |"), std::string::npos);
  EXPECT_NE(md.find("| `summary.json` | summary |"), std::string::npos);
  EXPECT_NE(md.find("| `/var/data/x.pcd` | elsewhere |"), std::string::npos);  // kept absolute
}

TEST(ReportTest, MissingCostmapIsSaid) {
  ReportContent c;
  c.title = "t";
  c.costmap_png = "/nonexistent/costmap.png";
  const std::string md = RenderMarkdown(c, "/tmp");
  EXPECT_NE(md.find("Costmap image missing"), std::string::npos);
}

TEST(ReportTest, UnwritablePathThrowsNamingIt) {
  ReportContent c;
  c.title = "t";
  try {
    WriteReport("/nonexistent/dir/report.md", c);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/report.md"), std::string::npos);
  }
}

}  // namespace
}  // namespace hylo::report
