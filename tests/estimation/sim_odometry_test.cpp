// Lidar-inertial odometry on simulated session A against the simulator's ground truth, for
// both lidar layouts, at the simulator's full resolution (0.2 deg columns) and the target
// length (120 s, > 100 m). About 30 s of CPU per layout (simulation included), which fits
// the CI budget; hylo_odometry_benchmark prints the same figures with timing.
#include <gtest/gtest.h>

#include "estimation/sim_odometry_util.h"

namespace hylo::sim {
// ctest lists the lidar by name rather than the enum's raw bytes.
inline void PrintTo(LidarModel model, std::ostream* os) { *os << ToString(model); }
}  // namespace hylo::sim

namespace hylo::testing {
namespace {

class SimOdometry : public ::testing::TestWithParam<sim::LidarModel> {};

TEST_P(SimOdometry, SessionAMeetsTheAccuracyBounds) {
  sim::SimulationOptions sim_options;
  sim_options.duration_a_s = 120.0;
  sim_options.seed = 5;
  sim_options.lidar.model = GetParam();
  sim::SessionSummary summary;
  const SimRun run = RunSimulatedSession(sim_options, sim::SessionId::kA,
                                         PipelineOptionsFor(sim_options), &summary);
  ASSERT_FALSE(run.failed) << run.message;
  const std::size_t scans = run.results.size();
  ASSERT_GT(scans, 0.9 * summary.scans - 15);  // all but the initialisation second
  std::size_t applied = 0;
  for (const auto& r : run.results) applied += r.update.applied ? 1 : 0;
  EXPECT_GE(applied + 1, scans);  // only the very first scan has no map to match
  const auto& ate = run.ate;
  std::printf("[%s] %zu scans, path %.1f m, ATE RMSE %.4f m (max %.4f), rot %.3f deg, "
              "end drift %.3f m = %.3f %%\n",
              sim::ToString(GetParam()).c_str(), scans, ate.path_length_m, ate.rmse_m, ate.max_m,
              ate.rotation_rmse_deg, ate.end_drift_m, ate.end_drift_percent);
  EXPECT_GE(ate.path_length_m, 100.0);
  EXPECT_LE(ate.rmse_m, 0.05);
  EXPECT_LE(ate.end_drift_percent, 0.3);
}

INSTANTIATE_TEST_SUITE_P(Lidars, SimOdometry,
                         ::testing::Values(sim::LidarModel::kVlp16, sim::LidarModel::kRs16),
                         [](const auto& info) { return sim::ToString(info.param); });

}  // namespace
}  // namespace hylo::testing
