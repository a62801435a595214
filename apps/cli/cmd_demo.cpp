// `hylo demo [--out DIR] [--quick]`: the paper's whole pipeline on the embedded simulated
// substation, into DIR/<timestamp>/ with a DIR/latest link:
//   1. simulate sessions A and B (a day apart; B has changed parts of the site);
//   2. SLAM on A with the IESKF -> the raw prior map (every registered scan);
//   3. craft it (uniform sampling + MLS), extract the ground (the configuration's ground
//      method, SMRF by default), build the costmap;
//   4. plan the inspection of session A's equipment on the crafted map (`hylo inspect`);
//   5. localize B in the crafted map from a rough guess, hybrid mode, with each back-end
//      (each in its own process, backend_runs.h);
//   6. evaluate (ATE/RPE against B's truth, c2c to the prior) and draw the figures;
//   7. write summary.json and report.md, print the table and the report's path.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>

#include "backend_runs.h"
#include "commands.h"
#include "demo_inspection.h"
#include "demo_report.h"
#include "demo_setup.h"
#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/io/json.h"
#include "hylo/report/report.h"
#include "hylo/run/run_log.h"
#include "hylo/sim_io/session_writer.h"
#include "run_figures.h"
#include "site_mapping_steps.h"

namespace hylo::cli {
namespace {

namespace fs = std::filesystem;

struct DemoArgs {
  std::string out = "out/demo";
  bool quick = false;
  uint64_t seed = 1;
};

// Numbered progress lines on stdout with the time since the demo started.
class Steps {
 public:
  void Start(const std::string& what) {
    std::printf("\n== [%d/7 %5.1f s] %s\n", ++index_, Elapsed(), what.c_str());
    std::fflush(stdout);
  }
  double Elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  int index_ = 0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// DIR/<local time stamp>, a new folder even for two runs in the same second; DIR/latest -> it.
std::string MakeRunDir(const std::string& out) {
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", std::localtime(&now));
  std::string name = stamp;
  for (int k = 2; fs::exists(out + "/" + name); ++k)
    name = std::string(stamp) + "-" + std::to_string(k);
  fs::create_directories(out + "/" + name);
  const fs::path latest = fs::path(out) / "latest";
  std::error_code ignored;
  fs::remove(latest, ignored);
  fs::create_directory_symlink(name, latest, ignored);  // a link is a convenience, not a must
  return out + "/" + name;
}

sim::SimulationOptions SimulationFor(const DemoArgs& args) {
  sim::SimulationOptions options;
  options.seed = args.seed;
  if (args.quick) {
    // Session B starts where A's route passes only after ~155 s: A keeps its full length so
    // the prior map covers B's start, and both are made cheaper with 1 deg lidar columns
    // (a fifth of the returns); B is cut to 30 s.
    options.duration_b_s = 30.0;
    options.lidar.column_deg = 1.0;
  }
  return options;
}

io::Json Simulate(const sim::SimulationOptions& options, const sim::Site& site,
                  const std::string& dir) {
  io::Json sessions = io::Json::array();
  for (const sim::SessionId id : {sim::SessionId::kA, sim::SessionId::kB}) {
    const sim::SessionSummary s = sim::WriteSession(options, site, id, dir);
    std::printf("  session %s: %.0f s, %zu scans, %.1f m driven (%.1f s wall)\n",
                sim::ToString(id).c_str(), s.duration_s, s.scans, s.path_length_m, s.elapsed_s);
    io::Json j = io::Json::object();
    j["session"] = sim::ToString(id);
    j["duration_s"] = s.duration_s;
    j["scans"] = s.scans;
    j["path_length_m"] = s.path_length_m;
    j["wall_s"] = s.elapsed_s;
    sessions.push_back(j);
  }
  sim::WriteSiteOutputs(options, site, sim::SiteOutputOptions(), dir);
  return sessions;
}

// SLAM on session A; returns its ATE (the alignment places B's truth in A's map frame).
evaluation::AteResult SlamSessionA(const DemoPaths& p, const config::RunConfig& config,
                                   io::Json* summary) {
  run::RunRequest request;
  request.log = p.bag_a;
  request.config = config;
  request.out_dir = p.slam_dir;
  request.label = "SLAM A";
  const run::RunResult result = run::RunLog(request);
  report::BackendRow row;
  const evaluation::AteResult ate = EvaluateTrajectory(result.trajectory, p.truth_a, 1.0, &row);
  *summary = result.summary;
  (*summary)["ate_rmse_m"] = row.ate_rmse_m;
  (*summary)["rpe_rmse_m"] = row.rpe_rmse_m;
  std::printf("  %zu scans, ATE RMSE %s m against the truth, %s ms/scan median\n",
              result.trajectory.size(), report::FormatFigure(row.ate_rmse_m, 4).c_str(),
              report::FormatFigure(io::NumberAt(result.summary, "ms_per_scan_median"), 2).c_str());
  return ate;
}

void RunDemo(const DemoArgs& args) {
  Steps steps;
  const DemoPaths p = MakeDemoPaths(MakeRunDir(args.out));
  std::printf("hylo demo%s: outputs in %s\n", args.quick ? " --quick" : "", p.dir.c_str());
  DemoSummary s;
  s.quick = args.quick;
  s.sim = SimulationFor(args);
  config::RunConfig config = ConfigForSimulation(s.sim);

  steps.Start("simulate sessions A and B of the substation (VLP-16 + 200 Hz IMU)");
  const sim::Site site = sim::BuildSite(s.sim.seed, s.sim.terrain);
  s.simulation = Simulate(s.sim, site, p.sim_dir);

  steps.Start("SLAM on session A with the IESKF: the raw prior map");
  const evaluation::AteResult ate_a = SlamSessionA(p, config, &s.slam);

  steps.Start("craft the map (uniform sampling + MLS), ground (" +
              std::string(terrain::ToString(config.ground.method)) +
              "), traversability costmap");
  fs::create_directories(p.map_dir);
  s.craft = CraftFile(p.slam_dir + "/map_dense.pcd", p.crafted_map, terrain::CraftOptions());
  std::printf("  crafted: %zu -> %zu points\n", s.craft.input_points, s.craft.output_points);
  s.ground = GroundFile(p.crafted_map, p.ground, p.objects, config.ground);
  std::printf("  ground (%s) %zu, objects %zu points\n", s.ground.method.c_str(),
              s.ground.ground_points, s.ground.object_points);
  s.traversability =
      TraversabilityFiles(p.ground, p.objects, p.costmap_dir, terrain::TraversabilityOptions());
  std::printf("  costmap %d x %d cells: %zu free, %zu cost, %zu lethal, %zu unknown\n",
              s.traversability.width, s.traversability.height, s.traversability.cells[1],
              s.traversability.cells[2], s.traversability.cells[3], s.traversability.cells[0]);

  steps.Start("plan the inspection of session A's equipment (hylo inspect)");
  s.inspection = InspectSite(site, ate_a, p.crafted_map, p.costmap_dir, p.inspection_dir);
  {
    const io::Json& t = s.inspection.plan.at("targets");
    std::printf("  %d of %d targets planned (%d occluded, %d unreachable), route %.1f m (%.1f s)\n",
                t.value("planned", 0), t.value("total", 0), t.value("occluded", 0),
                t.value("unreachable", 0), io::NumberAt(s.inspection.plan, "route.length_m"),
                s.inspection.seconds);
  }

  steps.Start(
      "localize session B in the crafted map from a rough guess, hybrid mode, "
      "each back-end");
  s.guess_world_imu = SessionBGuess(p.truth_b, ate_a, s.guess_error);
  config.pipeline.localization.update_after_s = s.hybrid_after_s;
  config::SaveRunConfig(p.localize_config, config);
  BackendRunsRequest request;
  request.log = p.bag_b;
  request.config_path = p.localize_config;
  request.prior_map = p.crafted_map;
  request.guess = PoseAsGuessText(s.guess_world_imu);
  request.ground_truth = p.truth_b;
  request.out_dir = p.localize_dir;
  const std::vector<BackendRun> runs = RunBackends(request);
  for (const BackendRun& run : runs) {
    s.prior_frame_error_m.push_back(run.trajectory.empty()
                                        ? std::nan("")
                                        : PriorFrameErrorRmse(run.trajectory, p.truth_b, ate_a));
  }

  steps.Start("evaluate and draw the figures");
  const std::vector<report::PlotFile> plots =
      DrawRunFigures(runs, p.truth_b, p.crafted_map, p.plot_dir);

  steps.Start("write the report");
  s.elapsed_s = steps.Elapsed();
  WriteDemoOutputs(p, s, runs, plots);
  std::vector<report::BackendRow> rows;
  for (const BackendRun& run : runs) rows.push_back(run.row);
  std::printf("\nLocalization of session B in the crafted map (%.0f s in all):\n\n%s\n",
              steps.Elapsed(), report::FormatTable(rows, report::TableStyle::kTerminal).c_str());
  for (const report::PlotFile& plot : plots) {
    if (!plot.ok) std::printf("plot missing: %s: %s\n", plot.path.c_str(), plot.message.c_str());
  }
  std::printf("summary: %s\nreport:  %s\n", p.summary.c_str(), p.report.c_str());
}

}  // namespace

void AddDemoCommand(CLI::App& root) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* cmd = root.add_subcommand(
      "demo", "The whole pipeline on the simulated substation, with a report per back-end");
  cmd->add_option("--out", args->out, "output folder (a time-stamped run folder + `latest`)")
      ->capture_default_str();
  cmd->add_flag("--quick", args->quick,
                "a first look in about a minute: session B 30 s instead of 150 s, lidar columns "
                "1 deg instead of 0.2 deg");
  cmd->add_option("--seed", args->seed, "simulation seed")->capture_default_str();
  cmd->callback([args]() { RunDemo(*args); });
}

}  // namespace hylo::cli
