// One scenario through SLAM and localization with every back-end, scored against the truth.
#include "estimation/scenario_run.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "estimation/scenario_sinks.h"
#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/mapping/prior_map.h"
#include "hylo/run/session.h"
#include "hylo/sim/scenario_simulator.h"
#include "hylo/sim_io/scenario_writer.h"

namespace hylo::testing {
namespace {

using estimation::Estimator;
using odometry::OdometryPipeline;
using evaluation::TimedPose;

constexpr double kDeg = M_PI / 180.0;

// A pipeline fed as a user's run would be (the configuration carries the sheet's clock offset).
// Finalized poses go back to the world frame (a prior map's local origin added).
class PipelineRun : public sim::SessionSink {
 public:
  explicit PipelineRun(const odometry::OdometryPipelineOptions& options)
      : session(options, run::SessionKeeps{true, false}), pipeline(session.pipeline()) {}
  void OnImu(const ImuSample& s) override { session.AddImu(s); }
  void OnScan(const LidarScan& s) override { session.AddScan(s); }
  void OnTruth(const sim::TruthSample&) override {}
  void Finish() {
    session.Finish();
    for (const estimation::NavState& x : states) {
      finalized.push_back(
          {x.t_ns, mapping::PoseToWorld(Eigen::Isometry3d(x.T_map_imu().Matrix()), origin_world)});
    }
  }

  run::Session session;
  OdometryPipeline& pipeline;  ///< session's
  const std::vector<odometry::ScanResult>& results = session.results();
  const std::vector<estimation::NavState>& states = session.finalized();  ///< map frame
  std::vector<TimedPose> finalized;  ///< the same states, world frame
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();
};

ModeFigures Score(const PipelineRun& run, const std::vector<TimedPose>& truth,
                  evaluation::Alignment alignment, std::size_t scans_simulated) {
  ModeFigures f;
  f.ran = true;
  std::vector<double> cpu, wall, process_cpu;
  for (const odometry::ScanResult& r : run.results) {
    cpu.push_back(r.cpu_ms);
    wall.push_back(r.total_ms);
    process_cpu.push_back(r.process_cpu_ms);
    f.not_applied += r.update.applied ? 0 : 1;
    f.degenerate += r.update.degenerate ? 1 : 0;
    f.out_of_time += r.update.out_of_time ? 1 : 0;
  }
  f.scans = run.results.size();
  f.calibration = run.pipeline.estimator().Calibration();
  f.searches = static_cast<std::size_t>(std::count_if(
      run.pipeline.events().begin(), run.pipeline.events().end(),
      [](const auto& e) { return e.kind == localization::LocalizationEvent::Kind::kSearching; }));
  f.cpu_ms_median = Percentile(cpu, 0.5);
  f.cpu_ms_p99 = Percentile(cpu, 0.99);
  f.wall_ms_median = Percentile(wall, 0.5);
  f.wall_ms_p99 = Percentile(wall, 0.99);
  f.process_cpu_ms_median = Percentile(process_cpu, 0.5);
  f.process_cpu_ms_p99 = Percentile(process_cpu, 0.99);
  if (run.pipeline.status() == OdometryPipeline::Status::kFailed) {
    f.failed = true;
    f.message = run.pipeline.message();
    return f;
  }
  if (run.finalized.size() < scans_simulated / 2) {
    f.failed = true;
    f.message = "only " + std::to_string(run.finalized.size()) + " of " +
                std::to_string(scans_simulated) + " scans got a pose";
    return f;
  }
  evaluation::AteOptions options;
  options.alignment = alignment;
  const evaluation::AteResult ate = evaluation::ComputeAte(run.finalized, truth, options);
  if (!ate.ok) {
    f.failed = true;
    f.message = ate.message;
    return f;
  }
  f.ate_m = ate.rmse_m;
  f.ate_max_m = ate.max_m;
  std::vector<TimedPose> live;
  for (const odometry::ScanResult& r : run.results) {
    if (r.pose_status != odometry::PoseStatus::kValid) continue;
    live.push_back({r.t_ns, mapping::PoseToWorld(Eigen::Isometry3d(r.state.T_map_imu().Matrix()),
                                                 run.origin_world)});
  }
  const evaluation::AteResult ate_live = evaluation::ComputeAte(live, truth, options);
  f.ate_live_m = ate_live.ok ? ate_live.rmse_m : std::nan("");
  f.rotation_rmse_deg = ate.rotation_rmse_deg;
  f.end_drift_m = ate.end_drift_m;
  f.end_drift_percent = ate.end_drift_percent;
  f.path_m = ate.path_length_m;
  f.end_error_se3_m = ate.translation_errors_m.empty() ? 0.0 : ate.translation_errors_m.back();
  // The end drift's direction: horizontal (heading, scale) or vertical (tilt, gravity).
  const evaluation::AssociatedPoses pairs = evaluation::Associate(run.finalized, truth);
  if (!pairs.estimate.empty()) {
    const Eigen::Isometry3d T = pairs.reference.front() * pairs.estimate.front().inverse();
    const Eigen::Vector3d error =
        (T * pairs.estimate.back()).translation() - pairs.reference.back().translation();
    f.end_drift_xy_m = error.head<2>().norm();
    f.end_drift_z_m = error.z();
  }
  return f;
}

void WriteTrace(const std::string& path, const PipelineRun& run,
                const std::vector<TimedPose>& truth) {
  std::ofstream out(path);
  out.precision(9);
  for (std::size_t i = 0; i < run.states.size(); ++i) {
    const estimation::NavState& x = run.states[i];
    Eigen::Isometry3d T_true;
    if (!evaluation::InterpolatePose(truth, x.t_ns, &T_true)) continue;
    const Eigen::Isometry3d& T_est = run.finalized[i].T_world_body;
    const Eigen::Quaterniond q_est(T_est.linear()), q_true(T_true.linear());
    out << 1e-9 * double(x.t_ns - run.states.front().t_ns) << ' ' << T_est.translation().transpose()
        << ' ' << q_est.coeffs().transpose() << ' ' << T_true.translation().transpose() << ' '
        << q_true.coeffs().transpose() << ' ' << x.accel_bias.transpose() << ' '
        << x.gyro_bias.transpose() << ' ' << x.gravity_map.transpose() << '\n';
  }
}

// Each scan's lidar update, one per line: time since the first scan (s), matches of points
// offered, applied, degenerate, the translation (0..1) and rotation (m²) information per match,
// RMS residual (m), iterations, map points, a zero-velocity update (standstill.h).
void WriteUpdates(const std::string& path, const PipelineRun& run) {
  std::ofstream out(path);
  if (run.results.empty()) return;
  const int64_t t0_ns = run.results.front().t_ns;
  for (const odometry::ScanResult& r : run.results) {
    const estimation::UpdateSummary& u = r.update;
    out << 1e-9 * double(r.t_ns - t0_ns) << ' ' << u.num_matches << ' ' << u.num_points << ' '
        << u.applied << ' ' << u.degenerate << ' ' << u.min_translation_information << ' '
        << u.min_rotation_information << ' ' << u.rms_residual_m << ' ' << u.iterations << ' '
        << r.map_points << ' ' << u.standstill << ' ' << r.deskew_ms << ' ' << r.update_ms << ' '
        << r.map_ms << ' ' << r.cpu_ms << '\n';
  }
}

// The localization events (start, searches, losses) one per line: why a start took long or
// failed, attempt by attempt.
void WriteEvents(const std::string& path, const PipelineRun& run) {
  std::ofstream out(path);
  for (const localization::LocalizationEvent& e : run.pipeline.events()) {
    out << 1e-9 * double(e.t_ns) << ' ' << localization::ToString(e.kind) << ": " << e.message
        << '\n';
  }
}

std::string TracePath(const ScenarioRunOptions& options, uint64_t number, const BackendFigures& run,
                      const char* mode) {
  return options.trace_dir + "/trace_" + std::to_string(number) + "_" + run.variant + "_" +
         estimation::ToString(run.backend) + "_" + mode + ".txt";
}

odometry::OdometryPipelineOptions OptionsFor(const config::RunConfig& config,
                                               Estimator::Backend backend, const Variant& variant) {
  odometry::OdometryPipelineOptions o = config.PipelineOptions();
  o.estimator.backend = backend;
  if (variant.adjust) variant.adjust(&o);
  return o;
}

}  // namespace

ScenarioFigures RunScenario(const sim::Scenario& scenario, const ScenarioRunOptions& options) {
  ScenarioFigures figures;
  figures.number = scenario.number;
  figures.summary = scenario.Summary();
  const auto runs_variant = [](const Variant& variant, Estimator::Backend backend) {
    return variant.backends.empty() || std::find(variant.backends.begin(), variant.backends.end(),
                                                 backend) != variant.backends.end();
  };
  for (const Variant& variant : options.variants) {
    for (const Estimator::Backend backend : options.backends) {
      if (runs_variant(variant, backend)) figures.runs.push_back({variant.name, backend, {}, {}});
    }
  }
  const sim::SensorSheet sheet = sim::SheetOf(scenario);
  const config::RunConfig config = sim::ScenarioRunConfig(sheet, options.preset_dir);
  const sim::Site site = sim::BuildScenarioSite(scenario);
  const auto each_run = [&](const std::function<void(const Variant&, Estimator::Backend)>& f) {
    for (const Variant& variant : options.variants) {
      for (const Estimator::Backend backend : options.backends) {
        if (runs_variant(variant, backend)) f(variant, backend);
      }
    }
  };

  // The mapping drive: SLAM with each back-end, and the true-pose map for localization.
  const sim::ScenarioSimulator drive_a(scenario, site, sim::SessionId::kA);
  const Eigen::Vector3d up =
      drive_a.motion().vehicle().PoseAt(0).linear() * Eigen::Vector3d::UnitZ();
  figures.start_tilt_deg = std::acos(std::min(1.0, up.z())) / kDeg;
  Tee tee_a;
  TruthTrack truth_a;
  tee_a.Add(&truth_a);
  std::vector<std::unique_ptr<PipelineRun>> slam;
  if (options.slam) {
    each_run([&](const Variant& variant, Estimator::Backend backend) {
      slam.push_back(std::make_unique<PipelineRun>(OptionsFor(config, backend, variant)));
      tee_a.Add(slam.back().get());
    });
  }
  std::unique_ptr<TruePoseMap> prior;
  if (options.localization) {
    prior = std::make_unique<TruePoseMap>(drive_a, options.prior_voxel_m);
    tee_a.Add(prior.get());
  }
  const sim::SessionSummary summary_a = drive_a.Run(&tee_a);
  figures.sim_cpu_s += summary_a.cpu_s;
  for (std::size_t k = 0; k < slam.size(); ++k) {
    slam[k]->Finish();
    figures.runs[k].slam =
        Score(*slam[k], truth_a.poses, evaluation::Alignment::kSE3, summary_a.scans);
    if (!options.trace_dir.empty()) {
      WriteUpdates(TracePath(options, scenario.number, figures.runs[k], "slam_updates"), *slam[k]);
      WriteTrace(TracePath(options, scenario.number, figures.runs[k], "slam"), *slam[k],
                 truth_a.poses);
    }
  }
  slam.clear();
  if (!options.localization) return figures;

  // The localization drive in that map, from a guess.
  std::vector<Eigen::Vector3d> prior_world = prior->PointsWorld();
  prior.reset();
  const mapping::PriorMap map = mapping::BuildPriorMap(prior_world, config.prior_map);
  std::vector<Eigen::Vector3d>().swap(prior_world);
  const sim::ScenarioSimulator drive_b(scenario, site, sim::SessionId::kB);
  const Eigen::Isometry3d guess = StartGuess(scenario, drive_b.motion().PoseAt(0));
  Tee tee_b;
  TruthTrack truth_b;
  tee_b.Add(&truth_b);
  std::vector<std::unique_ptr<PipelineRun>> localization;
  each_run([&](const Variant& variant, Estimator::Backend backend) {
    localization.push_back(std::make_unique<PipelineRun>(OptionsFor(config, backend, variant)));
    PipelineRun& run = *localization.back();
    run.origin_world = map.origin_world;
    run.pipeline.SetPriorMap(map.points_local);
    run.pipeline.SetInitialGuess(mapping::PoseToLocal(guess, map.origin_world));
    tee_b.Add(&run);
  });
  const sim::SessionSummary summary_b = drive_b.Run(&tee_b);
  figures.sim_cpu_s += summary_b.cpu_s;
  for (std::size_t k = 0; k < localization.size(); ++k) {
    localization[k]->Finish();
    figures.runs[k].localization =
        Score(*localization[k], truth_b.poses, evaluation::Alignment::kNone, summary_b.scans);
    if (!options.trace_dir.empty()) {
      WriteTrace(TracePath(options, scenario.number, figures.runs[k], "localization"),
                 *localization[k], truth_b.poses);
      WriteEvents(TracePath(options, scenario.number, figures.runs[k], "events"),
                  *localization[k]);
    }
  }
  return figures;
}

namespace {

io::Json ModeJson(const ModeFigures& f) {
  io::Json j = io::Json::object();
  j["failed"] = f.failed;
  if (!f.message.empty()) j["message"] = f.message;
  j["ate_m"] = f.ate_m;
  j["ate_max_m"] = f.ate_max_m;
  j["ate_live_m"] = f.ate_live_m;
  j["rotation_rmse_deg"] = f.rotation_rmse_deg;
  j["end_drift_m"] = f.end_drift_m;
  j["end_drift_percent"] = f.end_drift_percent;
  j["end_drift_xy_m"] = f.end_drift_xy_m;
  j["end_drift_z_m"] = f.end_drift_z_m;
  j["end_error_se3_m"] = f.end_error_se3_m;
  j["path_m"] = f.path_m;
  j["cpu_ms_median"] = f.cpu_ms_median;
  j["cpu_ms_p99"] = f.cpu_ms_p99;
  j["wall_ms_median"] = f.wall_ms_median;
  j["wall_ms_p99"] = f.wall_ms_p99;
  j["process_cpu_ms_median"] = f.process_cpu_ms_median;
  j["process_cpu_ms_p99"] = f.process_cpu_ms_p99;
  j["scans"] = f.scans;
  j["not_applied"] = f.not_applied;
  j["degenerate"] = f.degenerate;
  j["out_of_time"] = f.out_of_time;
  return j;
}

ModeFigures ModeFromJson(const io::Json& j) {
  ModeFigures f;
  f.ran = true;
  f.failed = j.at("failed").get<bool>();
  f.message = j.value("message", std::string());
  // NaN is written as null (a failed run's figures).
  const auto number = [&j](const char* key) {
    const io::Json& v = j.at(key);
    return v.is_null() ? std::nan("") : v.get<double>();
  };
  f.ate_m = number("ate_m");
  f.ate_max_m = number("ate_max_m");
  f.rotation_rmse_deg = number("rotation_rmse_deg");
  f.end_drift_m = number("end_drift_m");
  f.end_drift_percent = number("end_drift_percent");
  f.end_drift_xy_m = number("end_drift_xy_m");
  f.end_drift_z_m = number("end_drift_z_m");
  f.end_error_se3_m = number("end_error_se3_m");
  f.path_m = number("path_m");
  f.cpu_ms_median = number("cpu_ms_median");
  f.cpu_ms_p99 = number("cpu_ms_p99");
  // Absent from runs written before they were measured.
  const auto optional = [&](const char* key) {
    return j.contains(key) ? number(key) : std::nan("");
  };
  f.ate_live_m = optional("ate_live_m");
  f.wall_ms_median = optional("wall_ms_median");
  f.wall_ms_p99 = optional("wall_ms_p99");
  f.process_cpu_ms_median = optional("process_cpu_ms_median");
  f.process_cpu_ms_p99 = optional("process_cpu_ms_p99");
  f.scans = j.at("scans").get<std::size_t>();
  f.not_applied = j.at("not_applied").get<std::size_t>();
  f.degenerate = j.at("degenerate").get<std::size_t>();
  f.out_of_time = j.value("out_of_time", std::size_t{0});
  return f;
}

}  // namespace

ScenarioFigures FromJson(const io::Json& j) {
  ScenarioFigures f;
  try {
    f.number = j.at("number").get<uint64_t>();
    f.summary = j.at("summary").get<std::string>();
    f.start_tilt_deg = j.at("start_tilt_deg").get<double>();
    f.sim_cpu_s = j.at("sim_cpu_s").get<double>();
    for (const auto& [variant, backends] : j.at("runs").items()) {
      for (const auto& [name, modes] : backends.items()) {
        BackendFigures run;
        run.variant = variant;
        if (!estimation::ParseBackend(name, &run.backend)) {
          throw std::runtime_error("unknown back-end '" + name + "'");
        }
        if (modes.contains("slam")) run.slam = ModeFromJson(modes.at("slam"));
        if (modes.contains("localization")) {
          run.localization = ModeFromJson(modes.at("localization"));
        }
        f.runs.push_back(run);
      }
    }
  } catch (const io::Json::exception& e) {
    throw std::runtime_error("scenario " + std::to_string(f.number) + ": " + e.what());
  }
  return f;
}

io::Json ToJson(const ScenarioFigures& f) {
  io::Json j = io::Json::object();
  j["number"] = static_cast<unsigned long long>(f.number);
  j["summary"] = f.summary;
  j["start_tilt_deg"] = f.start_tilt_deg;
  j["sim_cpu_s"] = f.sim_cpu_s;
  for (const BackendFigures& run : f.runs) {
    const std::string name = estimation::ToString(run.backend);
    if (run.slam.ran) j["runs"][run.variant][name]["slam"] = ModeJson(run.slam);
    if (run.localization.ran) {
      j["runs"][run.variant][name]["localization"] = ModeJson(run.localization);
    }
  }
  return j;
}

}  // namespace hylo::testing
