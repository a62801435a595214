// The `threads` setting changes how fast a scan is processed, never the result: one simulated
// session fed at once to pipelines at 1, 2 and 4 threads, with each back-end, gives the same
// poses, matches and registered points to the last bit (each point's work writes only its own
// outputs, and sums run in point order). 4 threads is the cores on a smaller machine.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "estimation/sim_odometry_util.h"
#include "hylo/run/session.h"
#include "hylo/sim/simulator.h"

namespace hylo::testing {
namespace {

// One simulation into a session per thread count, each keeping everything it makes.
class FanOut : public sim::SessionSink {
 public:
  explicit FanOut(std::vector<std::unique_ptr<run::Session>>* sessions) : sessions_(*sessions) {}
  void OnImu(const ImuSample& s) override {
    for (auto& session : sessions_) session->AddImu(s);
  }
  void OnScan(const LidarScan& s) override {
    for (auto& session : sessions_) session->AddScan(s);
  }
  void OnTruth(const sim::TruthSample&) override {}

 private:
  std::vector<std::unique_ptr<run::Session>>& sessions_;
};

void ExpectSameStates(const estimation::NavState& a, const estimation::NavState& b,
                      const std::string& where) {
  EXPECT_EQ(a.t_ns, b.t_ns) << where;
  EXPECT_EQ(a.p_map_imu, b.p_map_imu) << where;
  EXPECT_EQ(a.R_map_imu.Matrix(), b.R_map_imu.Matrix()) << where;
  EXPECT_EQ(a.v_map_imu, b.v_map_imu) << where;
  EXPECT_EQ(a.T_imu_lidar.Matrix(), b.T_imu_lidar.Matrix()) << where;
}

class SimThreads : public ::testing::TestWithParam<estimation::Estimator::Backend> {};

TEST_P(SimThreads, PosesAreTheSameOnAnyNumberOfThreads) {
  const sim::SimulationOptions sim_options = sim::SimulationOptions::Fast(12.0);
  odometry::OdometryPipelineOptions options = PipelineOptionsFor(sim_options);
  options.estimator.backend = GetParam();
  options.output.dense_map_voxel_m = 0.1;  // the dense copy's sampling and deskew as well
  // A window solve stopped by its wall-time budget depends on the machine's load, at any
  // thread count: the budget is made ample here, and no solve may end on it (checked below).
  options.estimator.sliding_window.max_solver_time_s = 60.0;
  const std::vector<int> thread_counts = {1, 2, 4};
  std::vector<std::unique_ptr<run::Session>> sessions;
  for (const int threads : thread_counts) {
    options.threads = threads;
    sessions.push_back(std::make_unique<run::Session>(options));
  }
  const sim::Site site = sim::BuildSite(sim_options.seed, sim_options.terrain);
  FanOut fan_out(&sessions);
  sim::SessionSimulator(sim_options, site, sim::SessionId::kA).Run(&fan_out);
  for (auto& session : sessions) session->Finish();

  const run::Session& serial = *sessions.front();
  ASSERT_FALSE(serial.failed()) << serial.pipeline().message();
  ASSERT_GT(serial.results().size(), 80u);
  std::size_t matched = 0;
  for (const odometry::ScanResult& r : serial.results()) {
    matched += r.update.num_matches;
    ASSERT_FALSE(r.update.out_of_time) << "a solve ended on its time budget at " << r.t_ns;
  }
  // The loops are long enough to be split: thousands of points per scan.
  ASSERT_GT(matched / serial.results().size(), 1000u);
  ASSERT_GT(serial.dense_map().size(), 10000u);
  for (std::size_t k = 1; k < sessions.size(); ++k) {
    const run::Session& run = *sessions[k];
    const std::string threads = std::to_string(thread_counts[k]) + " threads";
    ASSERT_EQ(run.failed(), serial.failed()) << threads;
    ASSERT_EQ(run.results().size(), serial.results().size()) << threads;
    for (std::size_t i = 0; i < run.results().size(); ++i) {
      const odometry::ScanResult& a = serial.results()[i];
      const odometry::ScanResult& b = run.results()[i];
      const std::string where = threads + ", scan " + std::to_string(i);
      ASSERT_FALSE(b.update.out_of_time) << where << ": a solve ended on its time budget";
      ExpectSameStates(a.state, b.state, where);
      EXPECT_EQ(a.update.num_matches, b.update.num_matches) << where;
      EXPECT_EQ(a.update.iterations, b.update.iterations) << where;
      EXPECT_EQ(a.downsampled_points, b.downsampled_points) << where;
      if (::testing::Test::HasFailure()) return;  // the first scan that differs is enough
    }
    ASSERT_EQ(run.finalized().size(), serial.finalized().size()) << threads;
    for (std::size_t i = 0; i < run.finalized().size(); ++i) {
      ExpectSameStates(run.finalized()[i], serial.finalized()[i],
                       threads + ", finalized state " + std::to_string(i));
    }
    EXPECT_EQ(run.dense_map(), serial.dense_map()) << threads;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, SimThreads,
                         ::testing::Values(estimation::Estimator::Backend::kIeskf,
                                           estimation::Estimator::Backend::kSlidingWindow),
                         [](const auto& info) { return estimation::ToString(info.param); });

}  // namespace
}  // namespace hylo::testing
