// `hylo compare --log LOG [--map MAP --guess G] --config C [--gt GT] --out DIR`: the same log
// through every estimator back-end, each in its own child process so its peak memory
// is its own, each into DIR/<backend>/. One table (terminal, DIR/comparison.md,
// DIR/comparison.json): ATE and RPE against GT, the paper's cloud-to-cloud distance to the
// prior map, ms/scan median and p99, peak memory; plus the top-view and error plots.
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "backend_runs.h"
#include "commands.h"
#include "hylo/report/backend_table.h"
#include "hylo/report/report.h"
#include "run_figures.h"

namespace hylo::cli {
namespace {

struct CompareArgs {
  BackendRunsRequest request;
  std::string only_backend;  // set in the child process: run this one here
  std::string json;
};

std::string Caption(const BackendRunsRequest& r) {
  return "Each back-end ran on `" + r.log +
         "` in its own process. ATE: RMSE of the position "
         "error after SE(3) alignment to the ground truth; RPE: translation RMSE over " +
         report::FormatFigure(r.rpe_delta_m, 1) +
         " m of path; c2c: the paper's cloud-to-cloud "
         "distance of the run's registered scans to the prior map (n/a without one); ms/scan: "
         "wall time per scan (median, p99); CPU ms/scan: CPU time per scan (median); peak mem: "
         "VmHWM of the back-end's own process.";
}

report::ReportContent Content(const CompareArgs& args, const std::vector<BackendRun>& runs,
                              const std::vector<report::PlotFile>& plots) {
  const BackendRunsRequest& r = args.request;
  report::ReportContent c;
  c.title = "hylo compare";
  c.summary = r.prior_map.empty() ? "SLAM from scratch with each back-end."
                                  : "Localization in the prior map `" + r.prior_map +
                                        "` from the guess `" + r.guess + "`, with each back-end.";
  for (const BackendRun& run : runs) c.rows.push_back(run.row);
  c.table_caption = Caption(r);
  c.plots = plots;
  c.parameters = {{"log", r.log},
                  {"configuration", r.config_path},
                  {"prior map", r.prior_map.empty() ? "none (SLAM)" : r.prior_map},
                  {"ground truth", r.ground_truth.empty() ? "none" : r.ground_truth}};
  for (const BackendRun& run : runs) {
    c.files.push_back({run.row.backend + ": trajectory, maps, timing, summary", run.dir});
  }
  return c;
}

// The prior map, or for SLAM the map of the first back-end that finished.
std::string BackgroundMap(const BackendRunsRequest& request, const std::vector<BackendRun>& runs) {
  if (!request.prior_map.empty()) return request.prior_map;
  for (const BackendRun& run : runs) {
    if (run.row.status == report::RowStatus::kOk) return run.dir + "/map.pcd";
  }
  return "";
}

void RunCompare(const CompareArgs& args) {
  if (!args.only_backend.empty()) {  // the child side
    RunBackendHere(args.request, args.only_backend);
    return;
  }
  const std::vector<BackendRun> runs = RunBackends(args.request);
  std::vector<report::BackendRow> rows;
  for (const BackendRun& run : runs) rows.push_back(run.row);
  const std::string& out = args.request.out_dir;
  const auto plots = DrawRunFigures(runs, args.request.ground_truth,
                                    BackgroundMap(args.request, runs), out + "/plots");
  report::WriteReport(out + "/comparison.md", Content(args, runs, plots));
  io::Json json = io::Json::object();
  json["log"] = args.request.log;
  json["prior_map"] = args.request.prior_map;
  json["ground_truth"] = args.request.ground_truth;
  json["rpe_delta_m"] = args.request.rpe_delta_m;
  json["backends"] = report::TableToJson(rows);
  io::WriteJsonFile(out + "/comparison.json", json);
  MaybeWriteJson(args.json, json);
  std::printf("\n%s\n", report::FormatTable(rows, report::TableStyle::kTerminal).c_str());
  for (const report::PlotFile& p : plots) {
    if (!p.ok) std::printf("plot missing: %s: %s\n", p.path.c_str(), p.message.c_str());
  }
  std::printf("report: %s/comparison.md\n", out.c_str());
  bool any_finished = false;
  for (const report::BackendRow& row : rows) any_finished |= row.status == report::RowStatus::kOk;
  if (!any_finished) throw std::runtime_error("no back-end finished (see the table's notes)");
}

}  // namespace

void AddCompareCommand(CLI::App& root) {
  auto args = std::make_shared<CompareArgs>();
  BackendRunsRequest& r = args->request;
  CLI::App* cmd = root.add_subcommand(
      "compare", "The same log through every estimator back-end, compared in one table");
  cmd->add_option("--log", r.log, "the log: a ROS1 bag, a ROS 2 recording (rosbag2 directory or .mcap) or a scan folder")->required();
  cmd->add_option("--map", r.prior_map, "prior map (PCD/PLY): localize instead of SLAM");
  cmd->add_option("--guess", r.guess,
                  "with --map: T_world_imu guess, \"x y z roll pitch yaw\" (m, deg) or 16 "
                  "numbers (4x4 row-major)");
  cmd->add_option("--config", r.config_path, "run configuration (YAML)")->required();
  cmd->add_option("--gt", r.ground_truth, "ground-truth trajectory of the IMU (TUM)");
  cmd->add_option("--out", r.out_dir, "output folder (one sub-folder per back-end)")->required();
  cmd->add_option("--backends", r.backends, "back-ends to run, in order")
      ->check(CLI::IsMember(AllBackends()))
      ->capture_default_str();
  cmd->add_option("--rpe-delta", r.rpe_delta_m, "RPE pair spacing along the path, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--json", args->json, "also write the table as JSON here");
  // Internal: how the parent starts one back-end in a child process.
  cmd->add_option("--only-backend", args->only_backend)->group("");
  cmd->callback([args]() {
    if (!args->request.prior_map.empty() && args->request.guess.empty()) {
      throw std::invalid_argument("--map needs --guess \"x y z roll pitch yaw\"");
    }
    RunCompare(*args);
  });
}

}  // namespace hylo::cli
