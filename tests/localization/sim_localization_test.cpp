// Localization in a prior map on the simulator: session A is mapped by SLAM, then
// session B — a changed site with an annex A never entered — is localized in that map from a
// guess off by 2 m and 20 deg, with each back-end, in localization-only and hybrid mode.
// Prints a table like the paper's Table I. About 40 s of CPU per full session B run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "estimation/param_printers.h"
#include "estimation/sim_localization_util.h"
#include "hylo/evaluation/cloud_distance.h"
#include "hylo/mapping/ikd_tree.h"
#include "hylo/sim/surface_distance.h"
#include "hylo/sim/world.h"

namespace hylo::testing {
namespace {

using estimation::Estimator;
using localization::LocalizationEvent;

constexpr double kDegToRad = M_PI / 180.0;

sim::SimulationOptions SimOptions() { return sim::SimulationOptions(); }  // seed 1, as the demo

const sim::Site& SharedSite() {
  static const sim::Site site = sim::BuildSite(SimOptions().seed, SimOptions().terrain);
  return site;
}

// SLAM on session A once for every test of this executable.
const SimPrior& SharedPrior() {
  static const SimPrior prior = [] {
    SimPrior p = CachedSimPriorForThisBuild(SimOptions(), SharedSite(), "sim_prior_seed1");
    std::printf("prior map from SLAM on session A: %zu points, ATE %.4f m\n", p.points_map.size(),
                p.slam_ate.rmse_m);
    return p;
  }();
  return prior;
}

// The true start of session B in the prior's map frame, moved by (dx, dy) m and dyaw deg.
Eigen::Isometry3d PerturbedStart(const std::vector<evaluation::TimedPose>& truth_site, double dx,
                                 double dy, double dyaw_deg) {
  Eigen::Isometry3d guess = SharedPrior().T_site_map.inverse() * truth_site.front().T_world_body;
  guess.translation() += Eigen::Vector3d(dx, dy, 0.0);
  guess.linear() =
      Eigen::AngleAxisd(dyaw_deg * kDegToRad, Eigen::Vector3d::UnitZ()) * guess.linear();
  return guess;
}

// The simulator's B truth at the start, without running the session: the first truth sample.
std::vector<evaluation::TimedPose> SessionStartTruth(const sim::SimulationOptions& options) {
  struct FirstTruth : sim::SessionSink {
    void OnImu(const ImuSample&) override {}
    void OnScan(const LidarScan&) override {}
    void OnTruth(const sim::TruthSample& t) override {
      if (truth.empty()) truth.push_back({t.t_ns, t.T_map_imu});
    }
    std::vector<evaluation::TimedPose> truth;
  } sink;
  sim::SimulationOptions first = options;
  first.duration_b_s = 0.2;
  sim::SessionSimulator(first, SharedSite(), sim::SessionId::kB).Run(&sink);
  return sink.truth;
}

odometry::OdometryPipelineOptions LocalizationOptions(Estimator::Backend backend,
                                                        double update_after_s) {
  odometry::OdometryPipelineOptions o = PipelineOptionsFor(SimOptions());
  o.estimator.backend = backend;
  o.output.dense_map_voxel_m = 0.1;
  o.localization.update_after_s = update_after_s;
  return o;
}

struct LocalizationRun {
  std::unique_ptr<LocalizationSink> sink;
  evaluation::AteResult ate;       // finalized states against the truth, SE(3)-aligned
  evaluation::AteResult live_ate;  // live states, the same way
  evaluation::CloudDistanceSummary c2c;
};

// Runs session B (options' duration) localizing in the shared prior from `guess`.
LocalizationRun RunSessionB(
    const sim::SimulationOptions& sim_options, const odometry::OdometryPipelineOptions& options,
    const std::optional<Eigen::Isometry3d>& guess,
    const std::function<void(std::size_t, odometry::OdometryPipeline*)>& before_scan = {}) {
  LocalizationRun run;
  run.sink = std::make_unique<LocalizationSink>(options);
  run.sink->pipeline.SetPriorMap(SharedPrior().points_map);
  run.sink->pipeline.SetInitialGuess(guess);
  run.sink->before_scan = before_scan;
  sim::SessionSimulator(sim_options, SharedSite(), sim::SessionId::kB).Run(run.sink.get());
  run.sink->Finish();
  if (!run.sink->results().empty()) {
    run.ate = evaluation::ComputeAte(run.sink->Estimate(), run.sink->truth);
    run.live_ate = evaluation::ComputeAte(run.sink->LiveEstimate(), run.sink->truth);
    mapping::IkdTree reference{mapping::IkdTree::Options()};
    reference.Build(SharedPrior().points_map);
    run.c2c = evaluation::CloudToCloudDistance(run.sink->session.dense_map(), reference);
  }
  return run;
}

bool HasEvent(const odometry::OdometryPipeline& pipeline, LocalizationEvent::Kind kind) {
  for (const auto& e : pipeline.events()) {
    if (e.kind == kind) return true;
  }
  return false;
}

// One line per event, for a failure's message.
std::string EventList(const odometry::OdometryPipeline& pipeline) {
  std::string events;
  for (const LocalizationEvent& e : pipeline.events()) {
    events += std::string("\n  ") + ToString(e.kind) + ": " + e.message;
  }
  return events;
}

// The largest distance between the sink's map-frame poses from `from_t_ns` on and the truth
// carried into the prior's frame (no alignment); `compared` counts the poses.
double WorstPositionError(const LocalizationSink& sink, int64_t from_t_ns,
                          std::size_t* compared) {
  const Eigen::Isometry3d T_map_site = SharedPrior().T_site_map.inverse();
  double worst_m = 0.0;
  *compared = 0;
  for (const odometry::ScanResult& r : sink.results()) {
    if (r.t_ns < from_t_ns) continue;
    Eigen::Isometry3d T_site_imu;
    if (!evaluation::InterpolatePose(sink.truth, r.t_ns, &T_site_imu)) continue;
    const Eigen::Vector3d error = Eigen::Isometry3d(r.state.T_map_imu().Matrix()).translation() -
                                  (T_map_site * T_site_imu).translation();
    worst_m = std::max(worst_m, error.norm());
    ++*compared;
  }
  return worst_m;
}

class SimLocalization : public ::testing::TestWithParam<Estimator::Backend> {};

void PrintTableRow(const char* mode, Estimator::Backend backend, const LocalizationRun& run) {
  std::printf(
      "| %-13s | %-14s | c2c mean %.4f m | c2c std %.4f m | rejected %.1f %% | "
      "ATE RMSE %.4f m (live %.4f m) | rot %.3f deg |\n",
      mode, estimation::ToString(backend).c_str(), run.c2c.mean_m, run.c2c.std_m,
      100.0 * run.c2c.rejected_fraction, run.ate.rmse_m, run.live_ate.rmse_m,
      run.ate.rotation_rmse_deg);
}

TEST_P(SimLocalization, LocalizationOnlyFromAGuessOff2mAnd20Deg) {
  const sim::SimulationOptions sim_options = SimOptions();
  const Eigen::Isometry3d guess = PerturbedStart(SessionStartTruth(sim_options), 1.4, -1.4, 20.0);
  const LocalizationRun run =
      RunSessionB(sim_options, LocalizationOptions(GetParam(), -1.0), guess);
  const auto& pipeline = run.sink->pipeline;
  ASSERT_NE(pipeline.status(), odometry::OdometryPipeline::Status::kFailed) << pipeline.message();
  ASSERT_FALSE(pipeline.events().empty());
  EXPECT_EQ(pipeline.events().front().kind, LocalizationEvent::Kind::kInitialized);
  EXPECT_FALSE(HasEvent(pipeline, LocalizationEvent::Kind::kHybridStarted));
  EXPECT_EQ(pipeline.map().run_size(), 0u) << "localization only must not add points";
  EXPECT_EQ(pipeline.map().prior_size(), SharedPrior().points_map.size());
  ASSERT_TRUE(run.ate.ok) << run.ate.message;
  PrintTableRow("localization", GetParam(), run);
  EXPECT_GT(run.ate.path_length_m, 100.0);
  EXPECT_LE(run.ate.rmse_m, 0.03);
  EXPECT_LE(run.c2c.mean_m, 0.1);
  // Tracking that stays on the true pose must not be declared lost (the health check's false
  // alarms), even where the site changed since the prior was mapped.
  std::vector<double> inlier_ratios;
  for (const auto& r : run.sink->results()) inlier_ratios.push_back(r.health.inlier_ratio);
  std::sort(inlier_ratios.begin(), inlier_ratios.end());
  std::printf("health inlier ratio over %zu scans: min %.3f, median %.3f; bad scans %zu\n",
              inlier_ratios.size(), inlier_ratios.front(), inlier_ratios[inlier_ratios.size() / 2],
              pipeline.counters().scans_bad_health);
  EXPECT_FALSE(HasEvent(pipeline, LocalizationEvent::Kind::kLost));
}

TEST_P(SimLocalization, HybridModeExtendsTheMapOntoTheTrueSurfaces) {
  const sim::SimulationOptions sim_options = SimOptions();
  const Eigen::Isometry3d guess = PerturbedStart(SessionStartTruth(sim_options), -1.4, 1.4, -20.0);
  const LocalizationRun run = RunSessionB(sim_options, LocalizationOptions(GetParam(), 5.0), guess);
  const auto& pipeline = run.sink->pipeline;
  ASSERT_NE(pipeline.status(), odometry::OdometryPipeline::Status::kFailed) << pipeline.message();
  EXPECT_TRUE(HasEvent(pipeline, LocalizationEvent::Kind::kHybridStarted));
  ASSERT_TRUE(run.ate.ok) << run.ate.message;
  PrintTableRow("hybrid (5 s)", GetParam(), run);
  EXPECT_LE(run.ate.rmse_m, 0.03);
  // The prior is never windowed or changed; the run's points are what hybrid mode added.
  EXPECT_EQ(pipeline.map().prior_size(), SharedPrior().points_map.size());

  // Points added on the annex plateau (A never saw it), in the site frame through the
  // trajectory alignment, against the true surfaces of session B's world.
  const sim::Site& site = SharedSite();
  const sim::World world_b(site.terrain, sim::SessionPrimitives(site, sim::SessionId::kB),
                           sim_options.index_cell_m);
  const sim::SurfaceDistanceField truth(world_b);
  const Eigen::Vector2d margin(1.0, 1.0);
  double sum_m = 0.0;
  std::size_t count = 0;
  for (const Eigen::Vector3f& p_map : pipeline.map().FlattenRun()) {
    const Eigen::Vector3d p_site = run.ate.T_reference_estimate * p_map.cast<double>();
    const Eigen::Vector2d xy = p_site.head<2>();
    if ((xy.array() < (site.annex_min_m + margin).array()).any() ||
        (xy.array() > (site.annex_max_m - margin).array()).any()) {
      continue;
    }
    sum_m += truth.Nearest(p_site).distance_m;
    ++count;
  }
  ASSERT_GT(count, 200u) << "hybrid mode added no points in the annex";
  const double mean_m = sum_m / static_cast<double>(count);
  std::printf(
      "hybrid [%s]: %zu points added in the annex, mean distance to the true surfaces "
      "%.4f m\n",
      estimation::ToString(GetParam()).c_str(), count, mean_m);
  EXPECT_LE(mean_m, 0.05);
}

INSTANTIATE_TEST_SUITE_P(Backends, SimLocalization,
                         ::testing::Values(Estimator::Backend::kIeskf,
                                           Estimator::Backend::kSlidingWindow),
                         [](const auto& info) { return estimation::ToString(info.param); });

// ---- relocalization and bad input, on a 30 s session B with the IESKF ---------------------

sim::SimulationOptions ShortB() {
  sim::SimulationOptions o = SimOptions();
  o.duration_b_s = 30.0;
  return o;
}

TEST(SimRelocalization, ARequestNearTheTruePoseIsAccepted) {
  const auto truth = SessionStartTruth(ShortB());
  const Eigen::Isometry3d guess = PerturbedStart(truth, 0.5, 0.5, 5.0);
  const LocalizationRun run = RunSessionB(
      ShortB(), LocalizationOptions(Estimator::Backend::kIeskf, -1.0), guess,
      [](std::size_t scan, odometry::OdometryPipeline* pipeline) {
        if (scan != 150 || pipeline->status() != odometry::OdometryPipeline::Status::kRunning) {
          return;
        }
        // What a user's /initialpose would be: near, not exact.
        Eigen::Isometry3d request(pipeline->estimator().state().T_map_imu().Matrix());
        request.translation() += Eigen::Vector3d(0.8, -0.5, 0.0);
        request.linear() =
            Eigen::AngleAxisd(8.0 * kDegToRad, Eigen::Vector3d::UnitZ()) * request.linear();
        pipeline->RequestRelocalization(request);
      });
  const auto& pipeline = run.sink->pipeline;
  ASSERT_NE(pipeline.status(), odometry::OdometryPipeline::Status::kFailed) << pipeline.message();
  EXPECT_TRUE(HasEvent(pipeline, LocalizationEvent::Kind::kRelocalized));
  ASSERT_TRUE(run.ate.ok);
  EXPECT_LE(run.ate.rmse_m, 0.03);
  // The jump (a few mm here) went into map→odom, so odom→imu stays continuous.
  const odometry::ScanResult last = run.sink->results().back();
  const Eigen::Vector3d jump = last.T_map_odom.translation();
  EXPECT_LT(jump.norm(), 0.1);
}

TEST(SimRelocalization, ARequestAtAWrongPlaceIsRejectedAndTrackingContinues) {
  const auto truth = SessionStartTruth(ShortB());
  const LocalizationRun run =
      RunSessionB(ShortB(), LocalizationOptions(Estimator::Backend::kIeskf, -1.0),
                  PerturbedStart(truth, 0.5, 0.5, 5.0),
                  [](std::size_t scan, odometry::OdometryPipeline* pipeline) {
                    if (scan != 150) return;
                    Eigen::Isometry3d wrong(pipeline->estimator().state().T_map_imu().Matrix());
                    wrong.translation() += Eigen::Vector3d(35.0, 20.0, 0.0);
                    pipeline->RequestRelocalization(wrong);
                  });
  const auto& pipeline = run.sink->pipeline;
  ASSERT_NE(pipeline.status(), odometry::OdometryPipeline::Status::kFailed);
  EXPECT_TRUE(HasEvent(pipeline, LocalizationEvent::Kind::kRelocalizationFailed));
  EXPECT_FALSE(HasEvent(pipeline, LocalizationEvent::Kind::kRelocalized));
  ASSERT_TRUE(run.ate.ok);
  EXPECT_LE(run.ate.rmse_m, 0.03);
}

// An inlier ratio no scan can reach: every scan is bad, and the vehicle is lost every 40 scans
// while its estimate is in fact correct.
odometry::OdometryPipelineOptions EveryScanBadOptions() {
  odometry::OdometryPipelineOptions options =
      LocalizationOptions(Estimator::Backend::kIeskf, -1.0);
  options.localization.min_inlier_ratio = 1.0;
  options.localization.health_inlier_distance_m = 0.001;
  options.localization.lost_after_scans = 40;
  return options;
}

TEST(SimRelocalization, BadHealthDeclaresLossAndRelocalizes) {
  // The loss and the relocalization around the current pose must happen, and must not harm a
  // correct estimate.
  const odometry::OdometryPipelineOptions options = EveryScanBadOptions();
  const LocalizationRun run =
      RunSessionB(ShortB(), options, PerturbedStart(SessionStartTruth(ShortB()), 0.5, 0.5, 5.0));
  const auto& pipeline = run.sink->pipeline;
  ASSERT_NE(pipeline.status(), odometry::OdometryPipeline::Status::kFailed);
  EXPECT_TRUE(HasEvent(pipeline, LocalizationEvent::Kind::kLost));
  EXPECT_TRUE(HasEvent(pipeline, LocalizationEvent::Kind::kRelocalized));
  EXPECT_GT(pipeline.counters().scans_bad_health, 0u);
  ASSERT_TRUE(run.ate.ok);
  EXPECT_LE(run.ate.rmse_m, 0.03);
}

TEST(SimRelocalization, BesideTheScanPathTheFitNearTheLastPoseDoesNotHoldTheScan) {
  // As above, with the search's attempts on a worker (the ROS node's setting): the fit near
  // the last pose is the search's first attempt, so the scan that declared the loss goes on
  // in the provisional frame and a later scan applies the fit.
  odometry::OdometryPipelineOptions options = EveryScanBadOptions();
  options.localization.search.background = true;
  const LocalizationRun run =
      RunSessionB(ShortB(), options, PerturbedStart(SessionStartTruth(ShortB()), 0.5, 0.5, 5.0));
  const auto& pipeline = run.sink->pipeline;
  ASSERT_NE(pipeline.status(), odometry::OdometryPipeline::Status::kFailed);
  int64_t lost_t_ns = -1, relocalized_t_ns = -1;
  for (const LocalizationEvent& e : pipeline.events()) {
    if (e.kind == LocalizationEvent::Kind::kLost && lost_t_ns < 0) lost_t_ns = e.t_ns;
    if (e.kind == LocalizationEvent::Kind::kRelocalized && relocalized_t_ns < 0) {
      relocalized_t_ns = e.t_ns;
    }
  }
  ASSERT_GE(lost_t_ns, 0);
  ASSERT_GT(relocalized_t_ns, lost_t_ns) << "the fit was applied on the scan that was lost";
  std::size_t provisional = 0;
  for (const odometry::ScanResult& r : run.sink->all_results()) {
    if (r.pose_status == odometry::PoseStatus::kProvisional) ++provisional;
  }
  EXPECT_GT(provisional, 0u);
  ASSERT_TRUE(run.ate.ok);
  EXPECT_LE(run.ate.rmse_m, 0.03);
}

TEST(SimLocalizationBadInput, AGuessFarOutsideTheMapIsAClearErrorWithoutOdometry) {
  Eigen::Isometry3d far = PerturbedStart(SessionStartTruth(ShortB()), 400.0, -300.0, 0.0);
  odometry::OdometryPipelineOptions options =
      LocalizationOptions(Estimator::Backend::kIeskf, -1.0);
  options.localization.global_enabled = false;  // the guess alone
  const LocalizationRun run = RunSessionB(ShortB(), options, far);
  const auto& pipeline = run.sink->pipeline;
  EXPECT_EQ(pipeline.status(), odometry::OdometryPipeline::Status::kFailed);
  EXPECT_NE(pipeline.message().find("no start pose"), std::string::npos) << pipeline.message();
  EXPECT_TRUE(run.sink->results().empty()) << "no pose may be reported from a rejected start";
  EXPECT_TRUE(HasEvent(pipeline, LocalizationEvent::Kind::kInitializationFailed));
}

// Without a guess, or from a guess 500 m off, the global localizer finds the start in the
// whole prior map, and localization runs as from a good guess.
class SimGlobalStart : public ::testing::TestWithParam<bool> {};

TEST_P(SimGlobalStart, StartsWithoutAUsableGuess) {
  const bool with_far_guess = GetParam();
  std::optional<Eigen::Isometry3d> guess;
  if (with_far_guess) guess = PerturbedStart(SessionStartTruth(ShortB()), 400.0, -300.0, 0.0);
  const LocalizationRun run =
      RunSessionB(ShortB(), LocalizationOptions(Estimator::Backend::kIeskf, -1.0), guess);
  const auto& pipeline = run.sink->pipeline;
  ASSERT_NE(pipeline.status(), odometry::OdometryPipeline::Status::kFailed) << pipeline.message();
  ASSERT_FALSE(pipeline.events().empty());
  const LocalizationEvent& start = pipeline.events().front();
  EXPECT_EQ(start.kind, LocalizationEvent::Kind::kInitialized);
  EXPECT_NE(start.message.find("global localization accepted"), std::string::npos) << start.message;
  if (with_far_guess) {
    EXPECT_NE(start.message.find("guess rejected"), std::string::npos) << start.message;
  }
  ASSERT_TRUE(run.ate.ok);
  EXPECT_LE(run.ate.rmse_m, 0.03);
  // The start pose itself, against the truth in the prior's frame (not aligned).
  const Eigen::Isometry3d truth_map = PerturbedStart(SessionStartTruth(ShortB()), 0.0, 0.0, 0.0);
  EXPECT_LT((start.T_map_imu.translation() - truth_map.translation()).norm(), 0.1);
}

INSTANTIATE_TEST_SUITE_P(GuessOrNot, SimGlobalStart, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return std::string(info.param ? "FarGuess" : "NoGuess");
                         });

// Kidnapped: session B with 15 s cut out and the rest moved back in time, so the vehicle
// jumps to where it was 15 s later while the IMU says nothing happened. The supervisor loses
// it, fails around the last pose, finds it over the whole map, and tracking resumes.
TEST(SimRelocalization, AKidnappedVehicleIsFoundAgainOverTheWholeMap) {
  struct Kidnapped : LocalizationSink {
    using LocalizationSink::LocalizationSink;
    int64_t cut_from_ns = 0, cut_to_ns = 0;
    // False for data inside the cut; moves later stamps back by the cut's length.
    bool Keep(int64_t* t_ns) const {
      if (*t_ns >= cut_from_ns && *t_ns < cut_to_ns) return false;
      if (*t_ns >= cut_to_ns) *t_ns -= cut_to_ns - cut_from_ns;
      return true;
    }
    void OnImu(const ImuSample& s) override {
      ImuSample moved = s;
      if (Keep(&moved.t_ns)) LocalizationSink::OnImu(moved);
    }
    void OnScan(const LidarScan& s) override {
      LidarScan moved = s;
      if (!Keep(&moved.t_ns)) return;
      moved.end_t_ns = moved.t_ns + (s.end_t_ns - s.t_ns);  // the whole sweep moves
      LocalizationSink::OnScan(moved);
    }
    void OnTruth(const sim::TruthSample& t) override {
      sim::TruthSample moved = t;
      if (Keep(&moved.t_ns)) LocalizationSink::OnTruth(moved);
    }
  };
  sim::SimulationOptions sim_options = SimOptions();
  sim_options.duration_b_s = 45.0;
  Kidnapped sink(LocalizationOptions(Estimator::Backend::kIeskf, -1.0));
  sink.cut_from_ns = sim_options.start_b_ns + 12'000'000'000;
  sink.cut_to_ns = sim_options.start_b_ns + 27'000'000'000;
  sink.pipeline.SetPriorMap(SharedPrior().points_map);
  sink.pipeline.SetInitialGuess(PerturbedStart(SessionStartTruth(sim_options), 0.5, 0.5, 5.0));
  sim::SessionSimulator(sim_options, SharedSite(), sim::SessionId::kB).Run(&sink);
  sink.Finish();
  const auto& pipeline = sink.pipeline;
  ASSERT_NE(pipeline.status(), odometry::OdometryPipeline::Status::kFailed) << pipeline.message();

  // The jump, in the prior's frame: how far the vehicle was moved.
  Eigen::Isometry3d before_cut, after_cut;
  ASSERT_TRUE(evaluation::InterpolatePose(sink.truth, sink.cut_from_ns - 100'000'000, &before_cut));
  ASSERT_TRUE(evaluation::InterpolatePose(sink.truth, sink.cut_from_ns + 100'000'000, &after_cut));
  const double jump_m = (after_cut.translation() - before_cut.translation()).norm();
  EXPECT_GT(jump_m, 5.0) << "the cut must move the vehicle beyond the local search";

  const LocalizationEvent* relocalized = nullptr;
  for (const LocalizationEvent& e : pipeline.events()) {
    if (e.kind == LocalizationEvent::Kind::kRelocalized && e.t_ns >= sink.cut_from_ns) {
      relocalized = &e;
      break;
    }
  }
  const std::string events = EventList(pipeline);
  ASSERT_TRUE(HasEvent(pipeline, LocalizationEvent::Kind::kLost)) << events;
  ASSERT_NE(relocalized, nullptr) << "never found again" << events;
  EXPECT_NE(relocalized->message.find("global localization accepted"), std::string::npos)
      << relocalized->message;
  const double recovery_s = static_cast<double>(relocalized->t_ns - sink.cut_from_ns) * 1e-9;
  std::printf("kidnapped by %.1f m: found again %.2f s after the jump\n", jump_m, recovery_s);
  EXPECT_LE(recovery_s, 5.0);

  // From a second after the recovery on, the live poses are the truth's (no alignment).
  std::size_t compared = 0;
  const double worst_m =
      WorstPositionError(sink, relocalized->t_ns + 1'000'000'000, &compared);
  EXPECT_GT(compared, 50u);
  EXPECT_LT(worst_m, 0.1);
}

TEST(SimLocalizationBadInput, AnEmptyPriorMapIsAClearError) {
  LocalizationSink sink(LocalizationOptions(Estimator::Backend::kIeskf, -1.0));
  sink.pipeline.SetPriorMap({});
  sink.pipeline.SetInitialGuess(Eigen::Isometry3d::Identity());
  sim::SimulationOptions options = ShortB();
  options.duration_b_s = 3.0;
  sim::SessionSimulator(options, SharedSite(), sim::SessionId::kB).Run(&sink);
  sink.Finish();
  EXPECT_EQ(sink.pipeline.status(), odometry::OdometryPipeline::Status::kFailed);
  EXPECT_TRUE(sink.results().empty());
  EXPECT_FALSE(sink.pipeline.message().empty());
}

TEST(SimLocalizationMovingStart, ALogThatStartsWhileDrivingIsPlacedInTheMapWhileMoving) {
  // Session B from t = 10 s on: the vehicle is driving from the first sample, so there is
  // neither a standstill to initialise on nor a trustworthy guess (the one given is where the
  // session started, metres behind). The vehicle starts in a provisional frame and is found by
  // the search while it moves; nothing is reported in the map frame before that.
  struct LateStart : LocalizationSink {
    using LocalizationSink::LocalizationSink;
    int64_t start_ns = 0;
    void OnImu(const ImuSample& s) override {
      if (s.t_ns >= start_ns) LocalizationSink::OnImu(s);
    }
    void OnScan(const LidarScan& s) override {
      if (s.t_ns >= start_ns) LocalizationSink::OnScan(s);
    }
    void OnTruth(const sim::TruthSample& t) override {
      if (t.t_ns >= start_ns) LocalizationSink::OnTruth(t);
    }
  } sink(LocalizationOptions(Estimator::Backend::kIeskf, -1.0));
  sim::SimulationOptions options = ShortB();
  options.duration_b_s = 30.0;
  sink.start_ns = options.start_b_ns + 10'000'000'000;
  sink.pipeline.SetPriorMap(SharedPrior().points_map);
  sink.pipeline.SetInitialGuess(PerturbedStart(SessionStartTruth(options), 0.0, 0.0, 0.0));
  sim::SessionSimulator(options, SharedSite(), sim::SessionId::kB).Run(&sink);
  sink.Finish();
  const auto& pipeline = sink.pipeline;
  const std::string events = EventList(pipeline);
  ASSERT_NE(pipeline.status(), odometry::OdometryPipeline::Status::kFailed)
      << pipeline.message() << events;
  const LocalizationEvent* start = nullptr;
  for (const LocalizationEvent& e : pipeline.events()) {
    if (e.kind == LocalizationEvent::Kind::kInitialized) start = &e;
  }
  ASSERT_NE(start, nullptr) << events;
  const double found_after_s = static_cast<double>(start->t_ns - sink.start_ns) * 1e-9;
  std::printf("started on the move: placed in the map after %.2f s%s\n", found_after_s,
              events.c_str());
  ASSERT_FALSE(sink.results().empty());
  EXPECT_GE(sink.results().front().t_ns, start->t_ns);
  EXPECT_LT(sink.results().size(), sink.all_results().size()) << "the search's scans are provisional";
  std::size_t compared = 0;
  const double worst_m = WorstPositionError(sink, start->t_ns, &compared);
  EXPECT_GT(compared, 20u);
  EXPECT_LT(worst_m, 0.3) << events;
}

}  // namespace
}  // namespace hylo::testing
