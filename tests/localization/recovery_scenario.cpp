// One scenario's recovery cases: the prior, the cases' drive, every case's session, the scores.
#include "localization/recovery_scenario.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>

#include "estimation/scenario_sinks.h"
#include "hylo/common/time.h"
#include "hylo/mapping/prior_map.h"
#include "hylo/sim_io/scenario_writer.h"
#include "localization/recovery_trace.h"

namespace hylo::testing {
namespace {

using estimation::Estimator;

mapping::PriorMap TruePosePrior(const sim::Scenario& scenario, const sim::Site& site,
                                const mapping::PriorMapOptions& thinning, double voxel_m,
                                double* cpu_s) {
  const sim::ScenarioSimulator drive_a(scenario, site, sim::SessionId::kA);
  TruePoseMap map(drive_a, voxel_m);
  *cpu_s += drive_a.Run(&map).cpu_s;
  return mapping::BuildPriorMap(map.PointsWorld(), thinning);
}

std::vector<RecoveryCase> CasesFor(const sim::Scenario& scenario, const DriveTruth& truth,
                                   const RecoveryRunOptions& options) {
  if (options.specs.empty()) {
    std::vector<RecoveryCase> cases =
        DrawRecoveryCases(scenario.number, truth, scenario.site.yard_size_m, options.draw);
    if (!options.kinds.empty()) {
      std::vector<RecoveryCase> kept;
      for (const RecoveryCase& c : cases) {
        if (std::find(options.kinds.begin(), options.kinds.end(), c.kind) != options.kinds.end()) {
          kept.push_back(c);
        }
      }
      cases = kept;
    }
    return cases;
  }
  std::vector<RecoveryCase> cases;
  for (std::size_t k = 0; k < options.specs.size(); ++k) {
    const RecoveryCaseSpec& spec = options.specs[k];
    RecoveryCase c;
    if (!PlaceRecoveryCase(spec.kind, spec.after_motion_s, spec.distance_m, truth, options.draw,
                           &c)) {
      continue;
    }
    c.scenario = scenario.number;
    c.index = static_cast<int>(k);
    cases.push_back(c);
  }
  return cases;
}

// The mapping drive's route again, in the localization session's world, as long as it.
sim::ScenarioSimulator CasesDrive(const sim::Scenario& scenario, const sim::Site& site) {
  sim::Site drive_site = site;
  drive_site.route_b = site.route_a;
  sim::Scenario drive_scenario = scenario;
  drive_scenario.max_drive_b_s = scenario.max_drive_a_s;
  return sim::ScenarioSimulator(drive_scenario, drive_site, sim::SessionId::kB);
}

// Delivers the scans that fall in any case's window at the pace of their stamps (real_time),
// everything else at once. The pace restarts at each window's first scan: the drive between
// windows is not waited for.
class RealTimePacer : public sim::SessionSink {
 public:
  RealTimePacer(sim::SessionSink* sink, const std::vector<RecoveryCase>& cases)
      : sink_(sink), cases_(cases) {}
  void OnImu(const ImuSample& s) override { sink_->OnImu(s); }
  void OnTruth(const sim::TruthSample& t) override { sink_->OnTruth(t); }
  void OnScan(const LidarScan& s) override {
    if (InWindow(s.end_t_ns)) {
      const auto now = std::chrono::steady_clock::now();
      if (!pacing_) {
        pacing_ = true;
        anchor_wall_ = now;
        anchor_t_ns_ = s.end_t_ns;
      }
      std::this_thread::sleep_until(anchor_wall_ +
                                    std::chrono::nanoseconds(s.end_t_ns - anchor_t_ns_));
    } else {
      pacing_ = false;
    }
    sink_->OnScan(s);
  }

 private:
  bool InWindow(int64_t t_ns) const {
    for (const RecoveryCase& c : cases_) {
      if (t_ns >= c.return_t_ns && t_ns < c.end_t_ns) return true;
    }
    return false;
  }

  sim::SessionSink* sink_;
  std::vector<RecoveryCase> cases_;
  bool pacing_ = false;
  std::chrono::steady_clock::time_point anchor_wall_;
  int64_t anchor_t_ns_ = 0;
};

sim::Scenario Shortened(const sim::Scenario& drawn, const RecoveryRunOptions& options) {
  sim::Scenario scenario = drawn;
  if (options.max_drive_s > 0.0) scenario.max_drive_a_s = options.max_drive_s;
  return scenario;
}

}  // namespace

std::vector<RecoveryCase> PlanRecoveryCases(const sim::Scenario& drawn,
                                            const RecoveryRunOptions& options,
                                            std::vector<Eigen::Vector3d>* where_world) {
  const sim::Scenario scenario = Shortened(drawn, options);
  const sim::ScenarioSimulator drive = CasesDrive(scenario, sim::BuildScenarioSite(scenario));
  const DriveTruth truth(drive);
  const std::vector<RecoveryCase> cases = CasesFor(scenario, truth, options);
  where_world->clear();
  for (const RecoveryCase& c : cases) {
    where_world->push_back(truth.PoseAt(c.return_t_ns).translation());
  }
  return cases;
}

RecoveryScenario RunRecoveryScenario(const sim::Scenario& drawn,
                                     const RecoveryRunOptions& options) {
  const sim::Scenario scenario = Shortened(drawn, options);
  RecoveryScenario out;
  out.number = scenario.number;
  out.summary = scenario.Summary();
  const config::RunConfig config =
      sim::ScenarioRunConfig(sim::SheetOf(scenario), options.preset_dir);
  const sim::Site site = sim::BuildScenarioSite(scenario);
  const mapping::PriorMap prior =
      TruePosePrior(scenario, site, config.prior_map, options.prior_voxel_m, &out.cpu_s);

  const sim::ScenarioSimulator drive = CasesDrive(scenario, site);
  const DriveTruth truth(drive);
  out.drive_m = truth.DistanceAt(truth.end_ns());
  out.drive_s = NanosToSeconds(truth.end_ns() - truth.start_ns());
  const std::vector<RecoveryCase> cases = CasesFor(scenario, truth, options);
  const std::size_t wanted =
      options.specs.empty() ? static_cast<std::size_t>(options.draw.cases) : options.specs.size();
  out.cases_left_out = options.kinds.empty() ? static_cast<int>(wanted - cases.size()) : 0;

  const Eigen::Isometry3d guess = StartGuess(scenario, truth.PoseAt(truth.start_ns()));
  Tee tee;
  std::vector<std::unique_ptr<RecoveryRun>> runs;
  for (const RecoveryCase& c : cases) {
    for (const Estimator::Backend backend : options.backends) {
      odometry::OdometryPipelineOptions o = config.PipelineOptions();
      o.estimator.backend = backend;
      if (options.adjust) options.adjust(&o);
      std::optional<Eigen::Isometry3d> start_guess;
      if (c.kind != RecoveryKind::kMovingStart) start_guess = guess;
      runs.push_back(
          std::make_unique<RecoveryRun>(c, o, prior, start_guess, scenario.lidar_time_offset_ns));
      tee.Add(runs.back().get());
      out.results.push_back({c, backend, {}});
    }
  }
  RealTimePacer paced(&tee, cases);
  out.cpu_s += drive.Run(options.real_time ? static_cast<sim::SessionSink*>(&paced) : &tee).cpu_s;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    runs[k]->Finish();
    out.results[k].figures = ScoreRecovery(*runs[k], truth, options.score);
    if (!options.trace_dir.empty()) {
      WriteRecoveryTrace(*runs[k], truth, estimation::ToString(out.results[k].backend),
                         options.trace_dir);
    }
  }
  return out;
}

namespace {

io::Json CaseJson(const RecoveryCase& c) {
  return {{"index", c.index},           {"kind", ToString(c.kind)},
          {"cut_t_ns", c.cut_t_ns},     {"return_t_ns", c.return_t_ns},
          {"end_t_ns", c.end_t_ns},     {"drawn_distance_m", c.drawn_distance_m},
          {"distance_m", c.distance_m}, {"speed_mps", c.speed_mps}};
}

RecoveryCase CaseFromJson(uint64_t scenario, const io::Json& j) {
  RecoveryCase c;
  c.scenario = scenario;
  c.index = j.at("index").get<int>();
  if (!ParseRecoveryKind(j.at("kind").get<std::string>(), &c.kind)) {
    throw std::runtime_error("unknown case kind '" + j.at("kind").get<std::string>() + "'");
  }
  c.cut_t_ns = j.at("cut_t_ns").get<int64_t>();
  c.return_t_ns = j.at("return_t_ns").get<int64_t>();
  c.end_t_ns = j.at("end_t_ns").get<int64_t>();
  c.drawn_distance_m = j.at("drawn_distance_m").get<double>();
  c.distance_m = j.at("distance_m").get<double>();
  c.speed_mps = j.at("speed_mps").get<double>();
  return c;
}

}  // namespace

io::Json ToJson(const RecoveryScenario& s) {
  io::Json j = io::Json::object();
  j["number"] = static_cast<unsigned long long>(s.number);
  j["summary"] = s.summary;
  j["drive_m"] = s.drive_m;
  j["drive_s"] = s.drive_s;
  j["cpu_s"] = s.cpu_s;
  j["cases_left_out"] = s.cases_left_out;
  j["results"] = io::Json::array();
  for (const RecoveryResult& r : s.results) {
    j["results"].push_back({{"case", CaseJson(r.recovery_case)},
                            {"backend", estimation::ToString(r.backend)},
                            {"figures", ToJson(r.figures)}});
  }
  return j;
}

RecoveryScenario RecoveryScenarioFromJson(const io::Json& j) {
  RecoveryScenario s;
  try {
    s.number = j.at("number").get<uint64_t>();
    s.summary = j.at("summary").get<std::string>();
    s.drive_m = j.at("drive_m").get<double>();
    s.drive_s = j.at("drive_s").get<double>();
    s.cpu_s = j.at("cpu_s").get<double>();
    s.cases_left_out = j.at("cases_left_out").get<int>();
    for (const io::Json& r : j.at("results")) {
      RecoveryResult result;
      result.recovery_case = CaseFromJson(s.number, r.at("case"));
      const std::string backend = r.at("backend").get<std::string>();
      if (!estimation::ParseBackend(backend, &result.backend)) {
        throw std::runtime_error("unknown back-end '" + backend + "'");
      }
      result.figures = RecoveryFiguresFromJson(r.at("figures"));
      s.results.push_back(result);
    }
  } catch (const io::Json::exception& e) {
    throw std::runtime_error("scenario " + std::to_string(s.number) + ": " + e.what());
  }
  return s;
}

}  // namespace hylo::testing
