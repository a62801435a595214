// A scan joins the map at its finalized state (odometry_pipeline.h): at once with the filter,
// window_size - 1 scans later with the smoother, whose scans until then are searched from the
// window itself; the log's end brings the smoother's last window into the map. Both back-ends
// on a short simulated SLAM drive (VLP-16), with and without the smoother's scan pairs.
#include <gtest/gtest.h>

#include "estimation/sim_odometry_util.h"

namespace hylo::testing {
namespace {

using Backend = estimation::Estimator::Backend;

struct Case {
  Backend backend;
  bool scan_pairs;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << estimation::ToString(c.backend) << (c.scan_pairs ? " with pairs" : "");
}

class MapFromFinalized : public ::testing::TestWithParam<Case> {};

TEST_P(MapFromFinalized, ScansJoinTheMapWhenTheirStateIsFinal) {
  sim::SimulationOptions sim_options;
  sim_options.duration_a_s = 10.0;
  sim_options.seed = 5;
  sim_options.lidar.model = sim::LidarModel::kVlp16;
  odometry::OdometryPipelineOptions options = PipelineOptionsFor(sim_options);
  options.estimator.backend = GetParam().backend;
  options.estimator.sliding_window.scan_pairs = GetParam().scan_pairs;
  options.estimator.sliding_window.max_solver_time_s = 10.0;  // no dependence on the load
  const int window = options.estimator.sliding_window.window_size;
  const SimRun run = RunSimulatedSession(sim_options, sim::SessionId::kA, options);
  ASSERT_FALSE(run.failed) << run.message;
  ASSERT_GT(run.results.size(), 50u);

  std::size_t first_accepted = run.results.size(), first_in_map = run.results.size();
  for (std::size_t i = 0; i < run.results.size(); ++i) {
    if (run.results[i].map_updated && first_accepted == run.results.size()) first_accepted = i;
    if (run.results[i].map_points > 0 && first_in_map == run.results.size()) first_in_map = i;
  }
  ASSERT_LT(first_accepted, run.results.size());
  ASSERT_LT(first_in_map, run.results.size());
  if (GetParam().backend == Backend::kIeskf) {
    EXPECT_EQ(first_in_map, first_accepted);
    EXPECT_EQ(run.map_points, run.results.back().map_points);
  } else {
    // The first scan's state leaves the window when the window overflows.
    EXPECT_GE(first_in_map, first_accepted + window - 1);
    EXPECT_LE(first_in_map, first_accepted + window + 1);
    EXPECT_GT(run.map_points, run.results.back().map_points);  // the last window, at the end
  }
  // Every scan after the first was registered, the ones the map did not hold yet included.
  for (std::size_t i = first_accepted + 1; i < run.results.size(); ++i) {
    EXPECT_TRUE(run.results[i].update.applied)
        << "scan " << i << ": " << run.results[i].update.message;
  }
  std::printf("%s%s: ATE %.2f cm finalized, %.2f cm live\n",
              estimation::ToString(GetParam().backend).c_str(),
              GetParam().scan_pairs ? " with pairs" : "", 100 * run.ate.rmse_m,
              100 * run.live_ate.rmse_m);
  EXPECT_LE(run.ate.rmse_m, 0.05);
}

INSTANTIATE_TEST_SUITE_P(Backends, MapFromFinalized,
                         ::testing::Values(Case{Backend::kIeskf, false},
                                           Case{Backend::kSlidingWindow, false},
                                           Case{Backend::kSlidingWindow, true}),
                         [](const auto& info) {
                           return estimation::ToString(info.param.backend) +
                                  (info.param.scan_pairs ? "_pairs" : "");
                         });

}  // namespace
}  // namespace hylo::testing
