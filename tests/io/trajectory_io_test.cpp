#include "hylo/io/trajectory_io.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <random>

#include "test_data.h"

namespace hylo::io {
namespace {

std::vector<StampedPose> RandomTrajectory(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<StampedPose> poses;
  int64_t t_ns = 1630577758569490123;  // a Unix stamp with nanoseconds
  for (int i = 0; i < n; ++i) {
    StampedPose p;
    p.t_ns = t_ns;
    t_ns += 100000001 + i;
    p.position = Eigen::Vector3d(u(rng) * 1e5, u(rng) * 1e6, u(rng));
    p.orientation = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    poses.push_back(p);
  }
  return poses;
}

void Write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

void ExpectErrorMentions(const std::function<void()>& read, const std::string& a,
                         const std::string& b) {
  try {
    read();
    ADD_FAILURE() << "no error (expected '" << a << "', '" << b << "')";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(a), std::string::npos) << what;
    EXPECT_NE(what.find(b), std::string::npos) << what;
  }
}

TEST(SecondsText, ConvertsExactlyBothWays) {
  int64_t t = 0;
  ASSERT_TRUE(ParseSecondsToNs("1630577758.569490", &t));
  EXPECT_EQ(t, 1630577758569490000);
  ASSERT_TRUE(ParseSecondsToNs("1630577758.5694901239", &t));  // 10th decimal rounds up
  EXPECT_EQ(t, 1630577758569490124);
  ASSERT_TRUE(ParseSecondsToNs("-0.5", &t));
  EXPECT_EQ(t, -500000000);
  ASSERT_TRUE(ParseSecondsToNs("1.5e3", &t));
  EXPECT_EQ(t, 1500000000000);
  ASSERT_TRUE(ParseSecondsToNs("7", &t));
  EXPECT_EQ(t, 7000000000);
  for (const char* bad : {"", "-", ".", "1.2.3", "12a", "99999999999999"}) {
    EXPECT_FALSE(ParseSecondsToNs(bad, &t)) << bad;
  }
  EXPECT_EQ(FormatNsAsSeconds(1630577758569490123), "1630577758.569490123");
  EXPECT_EQ(FormatNsAsSeconds(-1), "-0.000000001");
  EXPECT_EQ(FormatNsAsSeconds(0), "0.000000000");
}

TEST(Tum, RoundTripIsExact) {
  const std::string path = hylo::testing::ScratchDir("tum_rt") + "/traj.tum";
  const std::vector<StampedPose> poses = RandomTrajectory(200, 1);
  WriteTum(path, poses);
  const std::vector<StampedPose> read = ReadTum(path);
  ASSERT_EQ(read.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read[i].t_ns, poses[i].t_ns);
    EXPECT_EQ(read[i].position, poses[i].position);
    // Written and re-normalised: equal to within rounding of the normalisation.
    EXPECT_LT((read[i].orientation.coeffs() - poses[i].orientation.coeffs()).norm(), 1e-15);
  }
}

TEST(Tum, ReadsCommentsAndRejectsWrongColumnCounts) {
  const std::string dir = hylo::testing::ScratchDir("tum_bad");
  Write(dir + "/ok.txt", "# header\n\n1.5 1 2 3 0 0 0 1\n  2.0 4 5 6 0 0 1 0  \n");
  const std::vector<StampedPose> poses = ReadTum(dir + "/ok.txt");
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[1].t_ns, 2000000000);
  EXPECT_EQ(poses[1].position, Eigen::Vector3d(4, 5, 6));
  EXPECT_NEAR(poses[1].orientation.angularDistance(
                  Eigen::Quaterniond(Eigen::AngleAxisd(EIGEN_PI, Eigen::Vector3d::UnitZ()))),
              0.0, 1e-12);
  Write(dir + "/seven.txt", "1.5 1 2 3 0 0 0 1\n2.0 1 2 3 0 0 1\n");
  ExpectErrorMentions([&] { ReadTum(dir + "/seven.txt"); }, dir + "/seven.txt",
                      "line 2: expected 8 columns");
  Write(dir + "/nine.txt", "# c\n1.5 1 2 3 0 0 0 1 9\n");
  ExpectErrorMentions([&] { ReadTum(dir + "/nine.txt"); }, "line 2", "found 9");
  Write(dir + "/nan.txt", "1.5 1 nan 3 0 0 0 1\n");
  ExpectErrorMentions([&] { ReadTum(dir + "/nan.txt"); }, "line 1", "not a finite number");
  Write(dir + "/quat.txt", "1.5 1 2 3 0 0 0 2\n");
  ExpectErrorMentions([&] { ReadTum(dir + "/quat.txt"); }, "line 1", "quaternion norm");
  ExpectErrorMentions([&] { ReadTum(dir + "/absent.txt"); }, "absent.txt", "cannot open");
}

TEST(Kitti, RoundTripWithTimesFile) {
  const std::string dir = hylo::testing::ScratchDir("kitti_rt");
  const std::vector<StampedPose> poses = RandomTrajectory(50, 2);
  WriteKitti(dir + "/poses.txt", poses, dir + "/times.txt");
  KittiTiming timing;
  timing.times_path = dir + "/times.txt";
  const std::vector<StampedPose> read = ReadKitti(dir + "/poses.txt", timing);
  ASSERT_EQ(read.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read[i].t_ns, poses[i].t_ns);
    EXPECT_EQ(read[i].position, poses[i].position);
    EXPECT_LT(read[i].orientation.angularDistance(poses[i].orientation), 1e-12);
  }
}

TEST(Kitti, PeriodTimingAndErrors) {
  const std::string dir = hylo::testing::ScratchDir("kitti_bad");
  Write(dir + "/p.txt", "1 0 0 1 0 1 0 2 0 0 1 3\n1 0 0 4 0 1 0 5 0 0 1 6\n");
  KittiTiming timing;
  timing.period_s = 0.25;
  timing.start_t_ns = 1000;
  const std::vector<StampedPose> read = ReadKitti(dir + "/p.txt", timing);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[1].t_ns, 250001000);
  EXPECT_EQ(read[1].position, Eigen::Vector3d(4, 5, 6));
  Write(dir + "/short.txt", "1 0 0 1 0 1 0 2 0 0 1\n");
  ExpectErrorMentions([&] { ReadKitti(dir + "/short.txt"); }, "line 1", "expected 12");
  Write(dir + "/scaled.txt", "2 0 0 1 0 2 0 2 0 0 2 3\n");
  ExpectErrorMentions([&] { ReadKitti(dir + "/scaled.txt"); }, "line 1", "not a rotation");
  Write(dir + "/times.txt", "0.0\n");
  timing.times_path = dir + "/times.txt";
  ExpectErrorMentions([&] { ReadKitti(dir + "/p.txt", timing); }, "times.txt", "fewer");
  timing.period_s = 0;
  std::string why;
  EXPECT_FALSE(timing.IsValid(&why));
  EXPECT_NE(why.find("period_s"), std::string::npos);
}

TEST(Kitti, ReadsTheOusterReferencePoses) {
  HYLO_REQUIRE_DATA("ouster/OS-1-128_v2.3.0_1024x10_lb_n3_poses_kitti.txt");
  const auto poses =
      ReadKitti(hylo::testing::DataPath("ouster/OS-1-128_v2.3.0_1024x10_lb_n3_poses_kitti.txt"));
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_TRUE(poses[0].position.isZero(0.0));
  EXPECT_NEAR(poses[2].position.x(), 0.4978255321866780214, 1e-15);
  EXPECT_EQ(poses[2].t_ns, 200000000);  // default 0.1 s period
}

}  // namespace
}  // namespace hylo::io
