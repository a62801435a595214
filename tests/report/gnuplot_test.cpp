// The gnuplot runner: a missing program, a failing script and a script that draws nothing each
// come back as ok = false with a reason (never a throw); a good script draws a real PNG with
// the installed gnuplot (skipped visibly when gnuplot is not installed).
#include "hylo/report/gnuplot.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "hylo/report/plots.h"
#include "test_data.h"

namespace hylo::report {
namespace {

bool HaveGnuplot() { return std::system("gnuplot --version > /dev/null 2>&1") == 0; }

// A stand-in "gnuplot": a shell script with a fixed behaviour.
std::string FakeProgram(const std::string& dir, const std::string& name, const std::string& body) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << "#!/bin/sh\n" << body << "\n";
  std::filesystem::permissions(path, std::filesystem::perms::owner_all);
  return path;
}

TEST(GnuplotTest, MissingProgramIsReportedNotThrown) {
  const std::string dir = testing::ScratchDir("gnuplot_missing");
  GnuplotOptions options;
  options.executable = dir + "/no-such-gnuplot";
  const GnuplotResult r = RenderPng(dir + "/a.png", "plot x", options);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.started);
  EXPECT_NE(r.message.find("cannot run"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("no-such-gnuplot"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("gnuplot-nox"), std::string::npos) << r.message;
  EXPECT_FALSE(std::filesystem::exists(dir + "/a.png"));
}

TEST(GnuplotTest, FailingProgramGivesStatusAndItsLastLineForBothTerminals) {
  const std::string dir = testing::ScratchDir("gnuplot_failing");
  GnuplotOptions options;
  options.executable =
      FakeProgram(dir, "fake", "echo 'line 3: undefined variable: foo' >&2\nexit 4");
  const GnuplotResult r = RenderPng(dir + "/a.png", "plot foo", options);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.started);
  EXPECT_NE(r.message.find("pngcairo: "), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("; png: "), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("status 4"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("undefined variable: foo"), std::string::npos) << r.message;
}

TEST(GnuplotTest, SuccessWithoutAnImageIsAFailure) {
  const std::string dir = testing::ScratchDir("gnuplot_noimage");
  GnuplotOptions options;
  options.executable = FakeProgram(dir, "fake", "exit 0");
  const GnuplotResult r = RenderPng(dir + "/a.png", "plot x", options);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("wrote no PNG"), std::string::npos) << r.message;
}

TEST(GnuplotTest, InvalidOptionsNameTheField) {
  GnuplotOptions options;
  options.width_px = 10;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("width_px = 10"), std::string::npos) << why;
  const GnuplotResult r = RenderPng("/tmp/unused.png", "plot x", options);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("width_px"), std::string::npos);
}

TEST(GnuplotTest, RealGnuplotScriptErrorIsReported) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed (apt-get install gnuplot-nox)";
  const std::string dir = testing::ScratchDir("gnuplot_error");
  const GnuplotResult r = RenderPng(dir + "/a.png", "plot undefined_function_xyz(x)");
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("undefined_function_xyz"), std::string::npos) << r.message;
}

TEST(GnuplotTest, RealGnuplotDrawsThePlots) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed (apt-get install gnuplot-nox)";
  const std::string dir = testing::ScratchDir("gnuplot_ok");
  std::vector<Eigen::Vector3d> map;
  for (int i = 0; i < 1000; ++i) map.emplace_back(i * 0.01, std::sin(i * 0.01), 0.0);
  TrajectoryLine truth{"ground truth", {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}}};
  TrajectoryLine est{"sliding_window", {{0, 0.1, 0}, {1, 1.1, 0}, {2, 0.1, 0}}};
  PlotOptions options;
  options.max_map_points = 100;
  const PlotFile top = PlotTopView(dir + "/top.png", "top view", map, {truth, est}, options);
  EXPECT_TRUE(top.ok) << top.message;
  EXPECT_TRUE(IsPngFile(dir + "/top.png"));
  // The map was subsampled to the limit: 100 map points, then the two lines.
  std::ifstream data(dir + "/top.dat");
  int numbers = 0;
  for (std::string line; std::getline(data, line) && !line.empty();) numbers += line[0] != '#';
  EXPECT_EQ(numbers, 100);
  const PlotFile err = PlotErrorOverTime(dir + "/err.png", "error",
                                         {{"ieskf", {0, 1, 2}, {0.01, 0.02, 0.015}}}, options);
  EXPECT_TRUE(err.ok) << err.message;
  EXPECT_TRUE(IsPngFile(dir + "/err.png"));
  EXPECT_GT(std::filesystem::file_size(dir + "/err.png"), 1000u);
}

TEST(GnuplotTest, NoCurvesIsAMissingPlotWithAReason) {
  const PlotFile err = PlotErrorOverTime("/tmp/unused.png", "error", {});
  EXPECT_FALSE(err.ok);
  EXPECT_FALSE(err.message.empty());
}

TEST(GnuplotTest, QuoteDoublesSingleQuotes) {
  EXPECT_EQ(GnuplotQuote("it's"), "'it''s'");
  EXPECT_EQ(GnuplotQuote("/a b/c.dat"), "'/a b/c.dat'");
}

}  // namespace
}  // namespace hylo::report
