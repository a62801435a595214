// `hylo eval c2c|ate|rpe` end to end: the built executable on small files written here, with
// figures computed by hand, read back from the JSON summary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "apps/cli_test_util.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/json.h"
#include "hylo/io/trajectory_io.h"
#include "test_data.h"

namespace hylo {
namespace {


using testing::ReadText;
// stdout is not looked at; stderr goes to `stderr_path`.
int RunHylo(const std::string& args, const std::string& stderr_path) {
  return testing::RunHylo(args, "/dev/null", stderr_path);
}

// A helix at 10 Hz, orientation following the heading; `transform` edits each position.
template <typename F>
std::vector<io::StampedPose> Helix(F transform) {
  std::vector<io::StampedPose> poses;
  for (int i = 0; i < 100; ++i) {
    const double a = 0.05 * i;
    io::StampedPose p;
    p.t_ns = i * 100'000'000LL;
    p.position = transform(Eigen::Vector3d(10 * std::cos(a), 10 * std::sin(a), 0.1 * a));
    p.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()));
    poses.push_back(p);
  }
  return poses;
}

class EvalCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::ScratchDir("eval_cli");
    io::WriteTum(Path("gt.txt"), Helix([](const Eigen::Vector3d& p) { return p; }));
  }
  std::string Path(const std::string& name) const { return dir_ + "/" + name; }
  std::string dir_;
};

TEST_F(EvalCliTest, C2cMatchesTheHandComputedCase) {
  io::CloudFile a, b;
  a.positions = {{0.1, 0, 0}, {0, 0.2, 0}, {10, 0, 0.3}, {9.6, 0, 0}, {5, 2, 0}};
  b.positions = {{0, 0, 0}, {10, 0, 0}};
  io::WriteCloud(Path("a.pcd"), a);
  io::WriteCloud(Path("b.pcd"), b);
  ASSERT_EQ(RunHylo("eval c2c --cloud " + Path("a.pcd") + " --ref " + Path("b.pcd") +
                        " --max-dist 1 --json " + Path("c2c.json"),
                    Path("err.txt")),
            0)
      << ReadText(Path("err.txt"));
  const io::Json json = io::ReadJsonFile(Path("c2c.json"));
  EXPECT_NEAR(io::NumberAt(json, "mean_m"), 0.25, 1e-6);
  EXPECT_NEAR(io::NumberAt(json, "std_m"), std::sqrt(0.0125), 1e-6);
  EXPECT_NEAR(io::NumberAt(json, "median_m"), 0.25, 1e-6);
  EXPECT_NEAR(io::NumberAt(json, "rejected_fraction"), 0.2, 1e-12);
  EXPECT_EQ(io::NumberAt(json, "count"), 4);
}

TEST_F(EvalCliTest, AteWithAndWithoutAlignment) {
  io::WriteTum(Path("shifted.txt"), Helix([](const Eigen::Vector3d& p) {
                 return Eigen::Vector3d(p + Eigen::Vector3d(0, 0.1, 0));
               }));
  io::WriteTum(Path("scaled.txt"), Helix([](const Eigen::Vector3d& p) {
                 return Eigen::Vector3d(0.5 * p + Eigen::Vector3d(3, 1, 0));
               }));
  const std::string base = "eval ate --gt " + Path("gt.txt") + " --json " + Path("ate.json");
  ASSERT_EQ(RunHylo(base + " --est " + Path("shifted.txt") + " --align none", Path("err.txt")), 0)
      << ReadText(Path("err.txt"));
  io::Json json = io::ReadJsonFile(Path("ate.json"));
  EXPECT_NEAR(io::NumberAt(json, "rmse_m"), 0.1, 1e-6);
  EXPECT_NEAR(io::NumberAt(json, "max_m"), 0.1, 1e-6);
  EXPECT_EQ(io::NumberAt(json, "num_poses"), 100);
  ASSERT_EQ(RunHylo(base + " --est " + Path("shifted.txt"), Path("err.txt")), 0);
  json = io::ReadJsonFile(Path("ate.json"));
  EXPECT_LT(io::NumberAt(json, "rmse_m"), 1e-6);
  // The alignment moves the estimate back by 0.1 m in y: row-major, the translation is the
  // last column (elements 3, 7, 11), the last row 0 0 0 1.
  const std::vector<double> T = json.at("T_reference_estimate").get<std::vector<double>>();
  ASSERT_EQ(T.size(), 16u);
  EXPECT_NEAR(T[3], 0.0, 1e-6);
  EXPECT_NEAR(T[7], -0.1, 1e-6);
  EXPECT_NEAR(T[11], 0.0, 1e-6);
  EXPECT_NEAR(T[15], 1.0, 1e-12);
  EXPECT_NEAR(T[12], 0.0, 1e-12);
  EXPECT_NEAR(T[13], 0.0, 1e-12);
  ASSERT_EQ(RunHylo(base + " --est " + Path("scaled.txt") + " --align sim3", Path("err.txt")), 0);
  json = io::ReadJsonFile(Path("ate.json"));
  EXPECT_NEAR(io::NumberAt(json, "scale"), 2.0, 1e-6);
  EXPECT_LT(io::NumberAt(json, "rmse_m"), 1e-5);
}

TEST_F(EvalCliTest, RpeOverFramesAndMetres) {
  // Every step 2 % longer: the 1-frame relative error is 2 % of the 0.5 m step.
  io::WriteTum(Path("long.txt"),
               Helix([](const Eigen::Vector3d& p) { return Eigen::Vector3d(1.02 * p); }));
  ASSERT_EQ(RunHylo("eval rpe --est " + Path("long.txt") + " --gt " + Path("gt.txt") + " --json " +
                        Path("rpe.json"),
                    Path("err.txt")),
            0)
      << ReadText(Path("err.txt"));
  io::Json json = io::ReadJsonFile(Path("rpe.json"));
  const double step_m = std::hypot(2 * 10 * std::sin(0.025), 0.005);  // chord of the helix
  EXPECT_NEAR(io::NumberAt(json, "rmse_m"), 0.02 * step_m, 1e-6);
  EXPECT_EQ(io::NumberAt(json, "num_pairs"), 99);
  ASSERT_EQ(RunHylo("eval rpe --est " + Path("long.txt") + " --gt " + Path("gt.txt") +
                        " --delta 5 --delta-unit m --json " + Path("rpe.json"),
                    Path("err.txt")),
            0);
  json = io::ReadJsonFile(Path("rpe.json"));
  // 10 chords make 4.9997 m < 5 m, so each pair spans 11 steps (0.55 rad, 5.5 cm up):
  // 2 % of that displacement, for i = 0..88.
  EXPECT_EQ(io::NumberAt(json, "num_pairs"), 89);
  EXPECT_NEAR(io::NumberAt(json, "mean_m"), 0.02 * std::hypot(20 * std::sin(0.275), 0.055), 1e-6);
}

TEST_F(EvalCliTest, BadInputEndsInOneLineAndAnError) {
  EXPECT_NE(
      RunHylo("eval ate --est " + Path("missing.txt") + " --gt " + Path("gt.txt"), Path("err.txt")),
      0);
  const std::string err = ReadText(Path("err.txt"));
  EXPECT_NE(err.find("missing.txt"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

}  // namespace
}  // namespace hylo
