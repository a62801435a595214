#include "demo_report.h"

#include <cmath>

#include "hylo/io/json.h"
#include "hylo/report/report.h"
#include "hylo/sim_io/session_writer.h"

namespace hylo::cli {
namespace {

std::string Fixed(double value, int decimals) { return report::FormatFigure(value, decimals); }

io::Json PlotsJson(const std::vector<report::PlotFile>& plots) {
  io::Json array = io::Json::array();
  for (const report::PlotFile& p : plots) {
    io::Json j = io::Json::object();
    j["title"] = p.title;
    j["path"] = p.path;
    j["ok"] = p.ok;
    if (!p.ok) j["message"] = p.message;
    array.push_back(j);
  }
  return array;
}

io::Json SummaryJson(const DemoPaths& p, const DemoSummary& s, const std::vector<BackendRun>& runs,
                     const std::vector<report::PlotFile>& plots) {
  io::Json j = io::Json::object();
  j["dir"] = p.dir;
  j["quick"] = s.quick;
  j["elapsed_s"] = s.elapsed_s;
  j["simulation"]["options"] = sim::OptionsToJson(s.sim);
  j["simulation"]["sessions"] = s.simulation;
  j["slam_a"] = s.slam;
  j["craft"] = s.craft.ToJson();
  j["ground"] = s.ground.ToJson();
  j["traversability"] = s.traversability.ToJson();
  j["inspection"] = s.inspection.ToJson();
  io::Json& loc = j["localization_b"];
  loc["guess_error"]["translation_m"] = s.guess_error.translation_m;
  loc["guess_error"]["yaw_deg"] = s.guess_error.yaw_deg;
  loc["update_after_s"] = s.hybrid_after_s;
  // Row-major: the transpose is evaluated into a matrix (an expression's data() would be the
  // column-major original).
  const Eigen::Matrix4d T_rows = s.guess_world_imu.matrix().transpose();
  loc["guess_T_map_imu"] = io::Json(std::vector<double>(T_rows.data(), T_rows.data() + 16));
  std::vector<report::BackendRow> rows;
  for (const BackendRun& run : runs) rows.push_back(run.row);
  loc["backends"] = report::TableToJson(rows);
  for (std::size_t i = 0; i < runs.size() && i < s.prior_frame_error_m.size(); ++i) {
    const double e = s.prior_frame_error_m[i];
    loc["error_in_prior_frame_rmse_m"][runs[i].row.backend] =
        std::isfinite(e) ? io::Json(e) : io::Json();
  }
  j["plots"] = PlotsJson(plots);
  j["report"] = p.report;
  return j;
}

std::string PriorFrameSentence(const DemoSummary& s, const std::vector<BackendRun>& runs) {
  std::string text =
      " Position RMSE without a new alignment (B's estimate taken into the truth's frame with "
      "session A's alignment, so it includes the prior map's own error):";
  for (std::size_t i = 0; i < runs.size() && i < s.prior_frame_error_m.size(); ++i) {
    text += (i == 0 ? " " : ", ") + runs[i].row.backend + " " + Fixed(s.prior_frame_error_m[i], 4) +
            " m";
  }
  return text + ".";
}

std::string Intro(const DemoSummary& s) {
  return "The paper's pipeline on the project's simulated substation: session A (" +
         Fixed(s.sim.duration_a_s, 0) +
         " s) mapped by SLAM with the IESKF, the map crafted "
         "(uniform sampling + MLS), its ground extracted (" + s.ground.method +
         ") and turned into a "
         "traversability costmap; then session B (" +
         Fixed(s.sim.duration_b_s, 0) +
         " s, a day later, with changed parts of the site) localized in the crafted map from a "
         "guess " +
         Fixed(s.guess_error.translation_m, 1) + " m and " + Fixed(s.guess_error.yaw_deg, 0) +
         " deg off the truth, in hybrid mode (the map grows "
         "after " +
         Fixed(s.hybrid_after_s, 0) +
         " s), with each estimator back-end. "
         "SLAM on session A: ATE RMSE " +
         Fixed(io::NumberAt(s.slam, "ate_rmse_m"), 4) + " m. Whole run: " + Fixed(s.elapsed_s, 0) +
         " s.";
}

std::vector<std::pair<std::string, std::string>> Parameters(const DemoSummary& s) {
  return {{"mode", s.quick ? "--quick" : "full"},
          {"simulation seed", std::to_string(s.sim.seed)},
          {"session A / B length",
           Fixed(s.sim.duration_a_s, 0) + " s / " + Fixed(s.sim.duration_b_s, 0) + " s"},
          {"lidar", sim::ToString(s.sim.lidar.model) + ", " + Fixed(s.sim.lidar.rate_hz, 0) +
                        " Hz, " + Fixed(s.sim.lidar.column_deg, 2) + " deg columns"},
          {"IMU", Fixed(s.sim.imu.rate_hz, 0) + " Hz"},
          {"initial guess error", Fixed(s.guess_error.translation_m, 2) + " m, " +
                                      Fixed(s.guess_error.yaw_deg, 1) + " deg yaw"},
          {"hybrid mode (map.update_after_s)", Fixed(s.hybrid_after_s, 1) + " s"},
          {"craft", "defaults of terrain::CraftOptions"},
          {"ground", s.ground.method + ", the configuration's ground section "
                                       "(terrain::GroundFilterOptions::ForRobotMaps)"},
          {"costmap resolution", Fixed(s.traversability.resolution_m, 2) + " m"}};
}

std::vector<report::OutputFile> Files(const DemoPaths& p, const std::vector<BackendRun>& runs) {
  std::vector<report::OutputFile> files{
      {"every figure of this run (JSON)", p.summary},
      {"simulated sessions: bags, true trajectories, manifests, site reference", p.sim_dir},
      {"SLAM on session A: trajectory, map.pcd, map_dense.pcd, timing, summary", p.slam_dir},
      {"crafted prior map, ground and object clouds", p.map_dir},
      {"costmap: map_server PGM + YAML, PNG, one ESRI ASCII grid per layer", p.costmap_dir},
      {"inspection of the equipment (`hylo inspect`): targets.csv, plan.csv, route.csv, "
       "visibility/, plan.png, summary.json",
       p.inspection_dir},
      {"effective configuration of the localization runs", p.localize_config}};
  for (const BackendRun& run : runs) {
    files.push_back({run.row.backend + " on session B: trajectory, map, timing, summary", run.dir});
  }
  files.push_back({"plot data and gnuplot scripts (redraw with `gnuplot <name>.gp`)", p.plot_dir});
  return files;
}

report::ImageSection InspectionSection(const DemoSummary& s) {
  const io::Json& plan = s.inspection.plan;
  const auto count = [&](const char* key) {
    return std::to_string(plan.at("targets").value(key, 0));
  };
  report::ImageSection section;
  section.title = "Inspection plan";
  section.text =
      "`hylo inspect` on the crafted map and its costmap: the targets are session A's equipment "
      "(insulator fittings, transformer tanks and bushings, pole tops, the building's "
      "air-conditioning unit, containers, sheds, drums, vehicles), taken into the map's frame "
      "with session A's alignment to the truth; the route starts where session A started. " +
      count("planned") + " of " + count("total") + " targets planned, " + count("occluded") +
      " occluded, " + count("unreachable") + " unreachable; route " +
      Fixed(io::NumberAt(plan, "route.length_m"), 1) + " m through " +
      std::to_string(plan.at("route").value("stops", 0)) + " stops; " +
      Fixed(s.inspection.seconds, 1) + " s.";
  section.image = s.inspection.dir + "/plan.png";
  section.caption =
      "Blue: the route; white squares: viewpoints, with their sight lines; crosses: targets "
      "(cyan planned, magenta occluded, orange unreachable); blue square: the start. Why each "
      "target was not planned: `inspection/plan.csv`.";
  return section;
}

}  // namespace

DemoPaths MakeDemoPaths(const std::string& dir) {
  DemoPaths p;
  p.dir = dir;
  p.sim_dir = dir + "/sim";
  p.bag_a = sim::SessionBagPath(p.sim_dir, sim::SessionId::kA);
  p.bag_b = sim::SessionBagPath(p.sim_dir, sim::SessionId::kB);
  p.truth_a = sim::SessionTruthPath(p.sim_dir, sim::SessionId::kA);
  p.truth_b = sim::SessionTruthPath(p.sim_dir, sim::SessionId::kB);
  p.slam_dir = dir + "/slam_a";
  p.map_dir = dir + "/map";
  p.crafted_map = p.map_dir + "/map_crafted.pcd";
  p.ground = p.map_dir + "/ground.pcd";
  p.objects = p.map_dir + "/objects.pcd";
  p.costmap_dir = dir + "/costmap";
  p.costmap_png = p.costmap_dir + "/costmap.png";
  p.inspection_dir = dir + "/inspection";
  p.localize_config = dir + "/localize_b.yaml";
  p.localize_dir = dir + "/localize_b";
  p.plot_dir = dir + "/plots";
  p.summary = dir + "/summary.json";
  p.report = dir + "/report.md";
  return p;
}

void WriteDemoOutputs(const DemoPaths& p, const DemoSummary& s, const std::vector<BackendRun>& runs,
                      const std::vector<report::PlotFile>& plots) {
  io::WriteJsonFile(p.summary, SummaryJson(p, s, runs, plots));
  report::ReportContent c;
  c.title = "hylo demo: localization and offline mapping of a simulated substation";
  c.summary = Intro(s);
  for (const BackendRun& run : runs) c.rows.push_back(run.row);
  c.table_caption =
      "Session B localized in the crafted map of session A. c2c: the paper's cloud-to-cloud "
      "distance of B's registered scans to the prior map (pairs beyond 0.5 m rejected); ATE: "
      "RMSE of the position error against the simulator's truth after SE(3) alignment; RPE: "
      "translation RMSE over 1 m of path; ms/scan: wall time per scan on this machine (median, "
      "99th percentile), CPU ms/scan: CPU time per scan (median; the fairer figure when the "
      "machine is shared); peak mem: VmHWM of the back-end's own process.";
  c.table_caption += PriorFrameSentence(s, runs);
  c.plots = plots;
  c.costmap_png = p.costmap_png;
  const auto& n = s.traversability.cells;
  c.costmap_caption =
      "Green: free, yellow to red: traversable at a rising cost, black: lethal "
      "(too steep, rough or high a step, or an obstacle), grey: unknown. Cells: " +
      std::to_string(n[1]) + " free, " + std::to_string(n[2]) + " cost, " + std::to_string(n[3]) +
      " lethal, " + std::to_string(n[0]) + " unknown at " +
      Fixed(s.traversability.resolution_m, 2) + " m.";
  c.sections.push_back(InspectionSection(s));
  c.parameters = Parameters(s);
  c.files = Files(p, runs);
  report::WriteReport(p.report, c);
}

}  // namespace hylo::cli
