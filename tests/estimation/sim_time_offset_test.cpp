// A lidar whose clock is 20 ms behind the IMU's (the simulator stamps session B's scans 20 ms
// early: t_imu = t_lidar + 0.02 s), localized in the SLAM map of session A with each back-end.
// Left uncorrected, every scan is registered as if taken 20 ms before it was, so every pose is
// the vehicle's 20 ms later (~2.4 cm along the path at 1.2 m/s); `lidar.time_offset_s: 0.02`
// restores the synchronised run. The ATE is taken in the site frame without alignment (a
// localizer's poses are absolute), which is where a time offset shows; after an SE(3)
// alignment part of it would be absorbed into the fitted transform. Prints the three ATEs.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "estimation/param_printers.h"
#include "estimation/sim_localization_util.h"
#include "hylo/common/time.h"

namespace hylo::testing {
namespace {

using Backend = estimation::Estimator::Backend;

constexpr double kOffsetS = 0.02;  // t_imu = t_lidar + kOffsetS

/// Seed 1 as the demo; session B shortened to 60 s and stamped with `offset_s`.
sim::SimulationOptions SimOptions(double offset_s) {
  sim::SimulationOptions o;
  o.duration_b_s = 60.0;
  // The simulator's option is the lidar clock minus true (IMU) time.
  o.lidar.time_offset_ns = -SecondsToNanos(offset_s);
  return o;
}

const sim::Site& SharedSite() {
  static const sim::Site site = sim::BuildSite(SimOptions(0.0).seed, SimOptions(0.0).terrain);
  return site;
}

// SLAM on the synchronised session A once per build of this test (see sim_localization_test).
const SimPrior& SharedPrior() {
  static const SimPrior prior = [] {
    return CachedSimPriorForThisBuild(SimOptions(0.0), SharedSite(), "sim_prior_offset_seed1");
  }();
  return prior;
}

/// Session B localized from its true start (0.3 m, 3 deg off); the finalized states' ATE in
/// the site frame, without alignment.
evaluation::AteResult LocalizeSessionB(Backend backend, double log_offset_s,
                                       double config_offset_s) {
  const sim::SimulationOptions sim_options = SimOptions(log_offset_s);
  odometry::OdometryPipelineOptions o = PipelineOptionsFor(sim_options);
  o.estimator.backend = backend;
  o.estimator.sliding_window.max_solver_time_s = 10.0;  // no wall-time cut (loaded machines)
  o.localization.update_after_s = -1.0;
  o.lidar.time_offset_s = config_offset_s;
  const sim::SessionSimulator simulator(sim_options, SharedSite(), sim::SessionId::kB);
  LocalizationSink sink(o);
  sink.pipeline.SetPriorMap(SharedPrior().points_map);
  Eigen::Isometry3d guess = SharedPrior().T_site_map.inverse() * simulator.trajectory().PoseAt(0);
  guess.translation() += Eigen::Vector3d(0.2, -0.2, 0.0);
  guess.linear() = Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()) * guess.linear();
  sink.pipeline.SetInitialGuess(guess);
  simulator.Run(&sink);
  sink.Finish();
  EXPECT_NE(sink.pipeline.status(), odometry::OdometryPipeline::Status::kFailed)
      << sink.pipeline.message();
  std::vector<evaluation::TimedPose> estimate_site = sink.Estimate();
  for (evaluation::TimedPose& p : estimate_site) {
    p.T_world_body = SharedPrior().T_site_map * p.T_world_body;
  }
  EXPECT_GT(estimate_site.size(), 400u);
  evaluation::AteOptions ate;
  ate.alignment = evaluation::Alignment::kNone;
  return evaluation::ComputeAte(estimate_site, sink.truth, ate);
}

class SimTimeOffset : public ::testing::TestWithParam<Backend> {};

TEST_P(SimTimeOffset, UncorrectedOffsetDegradesAteAndTheCorrectionRestoresIt) {
  const evaluation::AteResult synced = LocalizeSessionB(GetParam(), 0.0, 0.0);
  const evaluation::AteResult uncorrected = LocalizeSessionB(GetParam(), kOffsetS, 0.0);
  const evaluation::AteResult corrected = LocalizeSessionB(GetParam(), kOffsetS, kOffsetS);
  std::printf(
      "[%s] localization ATE RMSE (site frame, no alignment): synchronised %.4f m, "
      "20 ms offset uncorrected %.4f m, corrected %.4f m (rotation %.3f / %.3f / %.3f "
      "deg)\n",
      estimation::ToString(GetParam()).c_str(), synced.rmse_m, uncorrected.rmse_m, corrected.rmse_m,
      synced.rotation_rmse_deg, uncorrected.rotation_rmse_deg, corrected.rotation_rmse_deg);
  EXPECT_GT(uncorrected.rmse_m, 1.3 * synced.rmse_m);
  EXPECT_LE(corrected.rmse_m, 1.1 * synced.rmse_m + 0.002);
}

INSTANTIATE_TEST_SUITE_P(Backends, SimTimeOffset,
                         ::testing::Values(Backend::kIeskf, Backend::kSlidingWindow),
                         [](const auto& info) { return estimation::ToString(info.param); });

TEST(PipelineLidarOptions, TheOffsetIsValidatedAndConvertedToNanoseconds) {
  odometry::PipelineLidarOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why));
  for (const double bad : {1.5, -2.0, std::nan(""), HUGE_VAL}) {
    o.time_offset_s = bad;
    EXPECT_FALSE(o.IsValid(&why)) << bad;
    EXPECT_NE(why.find("time_offset_s"), std::string::npos) << why;
  }
  o.time_offset_s = -0.0125;
  EXPECT_TRUE(o.IsValid(&why));
  EXPECT_EQ(o.TimeOffsetNs(), -12'500'000);
}

}  // namespace
}  // namespace hylo::testing
