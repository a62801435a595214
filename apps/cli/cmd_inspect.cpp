// `hylo inspect --map CRAFTED --costmap DIR --targets FILE --out DIR`: where the robot must
// stand to see each target (sight lines through the crafted map) and the route there on the
// costmap; writes plan.csv, route.csv, visibility/, plan.png and summary.json
// (hylo/io/inspection_io.h).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"
#include "hylo/config/run_config.h"
#include "hylo/io/progress.h"
#include "hylo/io/text.h"
#include "hylo/run/inspection_run.h"

namespace hylo::cli {
namespace {

// "<what> (default <value>)" for a flag's help.
std::string WithDefault(const std::string& what, double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return what + " (default " + text + ")";
}

struct InspectArgs {
  std::string map_path, costmap_dir, targets_path, out_dir, json_path, config_path, start;
  // Flags that override the configuration when given (CLI11 counts them).
  double camera_height_m = 0, min_range_m = 0, max_range_m = 0, clearance_m = 0, voxel_m = 0,
         robot_radius_m = 0;
  bool no_return = false;
  CLI::App* cmd = nullptr;
};

inspection::InspectionOptions Options(const InspectArgs& a) {
  const inspection::InspectionOptions configured =
      a.config_path.empty() ? inspection::InspectionOptions()
                            : config::LoadRunConfig(a.config_path).inspection;
  // CLI11 counts the flags given: only those override the configuration.
  const auto given = [&](const char* flag, double value) {
    return a.cmd->count(flag) > 0 ? std::optional<double>(value) : std::nullopt;
  };
  run::InspectionOverrides o;
  o.camera_height_m = given("--camera-height", a.camera_height_m);
  o.min_range_m = given("--min-range", a.min_range_m);
  o.max_range_m = given("--max-range", a.max_range_m);
  o.clearance_m = given("--clearance", a.clearance_m);
  o.voxel_m = given("--voxel", a.voxel_m);
  o.robot_radius_m = given("--robot-radius", a.robot_radius_m);
  if (a.no_return) o.return_to_start = false;
  return run::WithOverrides(configured, o);
}

// "x y" in the map frame; the map frame's origin when empty.
Eigen::Vector2d ParseStart(const std::string& text) {
  if (text.empty()) return Eigen::Vector2d::Zero();
  const std::vector<std::string> words = io::SplitWords(text);
  Eigen::Vector2d xy;
  char* end = nullptr;
  for (int i = 0; i < 2 && words.size() == 2; ++i) {
    xy[i] = std::strtod(words[i].c_str(), &end);
    if (*end != '\0' || !std::isfinite(xy[i])) break;
    if (i == 1) return xy;
  }
  throw std::invalid_argument("--start '" + text + "': expected two numbers \"x y\" (map frame, m)");
}

void PrintPlan(const inspection::InspectionPlan& plan, const std::vector<inspection::Target>& targets) {
  const inspection::InspectionSummary& s = plan.summary;
  std::printf("targets: %zu planned, %zu occluded, %zu unreachable of %zu\n", s.planned,
              s.occluded, s.unreachable, targets.size());
  std::printf("route: %.1f m through %zu stops (%s tour)\n", s.route_length_m, plan.stops.size(),
              inspection::TourMethodName(s.tour_method));
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const inspection::TargetPlan& t = plan.targets[i];
    if (t.status == inspection::TargetStatus::kPlanned) continue;
    std::printf("  %s %s: %s\n", targets[i].id.c_str(), inspection::TargetStatusName(t.status),
                t.reason.c_str());
  }
  std::printf("seconds: occupancy %.2f, reach %.2f, visibility %.2f, travel costs %.2f, tour "
              "%.3f, route %.2f\n", s.seconds_occupancy, s.seconds_reach, s.seconds_visibility,
              s.seconds_travel_costs, s.seconds_tour, s.seconds_route);
}

void Run(const InspectArgs& args) {
  const inspection::InspectionOptions options = Options(args);
  const Eigen::Vector2d start_map = ParseStart(args.start);
  std::fprintf(stderr, "reading %s, %s and %s\n", args.costmap_dir.c_str(),
               args.targets_path.c_str(), args.map_path.c_str());
  const run::InspectionInputs inputs =
      run::ReadInspectionInputs(args.map_path, args.costmap_dir, args.targets_path);
  const terrain::GridGeometry& g = inputs.costmap.grid.geometry();
  std::fprintf(stderr, "planning %zu targets on %d x %d cells, %zu map points\n",
               inputs.targets_local.size(), g.width, g.height, inputs.map_local.size());
  std::unique_ptr<io::Progress> progress;
  std::string stage;
  const auto on_progress = [&](const std::string& name, std::size_t done, std::size_t total) {
    if (name != stage) {
      progress = std::make_unique<io::Progress>(name, total);
      stage = name;
    }
    progress->Update(done);
  };
  run::InspectionRun plan;
  try {
    plan = run::PlanInspectionRun(inputs, start_map, options, on_progress);
  } catch (const run::InspectionStartError& e) {
    throw std::runtime_error(e.what() + std::string(" (give --start \"x y\")"));
  }
  progress.reset();
  const std::vector<std::string> files = run::WriteInspectionRun(args.out_dir, inputs, plan);
  PrintPlan(plan.plan, inputs.targets_local);
  std::printf("wrote %zu files to %s\n", files.size(), args.out_dir.c_str());
  if (!args.json_path.empty()) {
    io::Json summary = plan.summary;
    for (const std::string& f : files) summary["outputs"].push_back(f);
    MaybeWriteJson(args.json_path, summary);
  }
}

}  // namespace

void AddInspectCommand(CLI::App& root) {
  static InspectArgs args;
  auto* cmd = root.add_subcommand(
      "inspect",
      "Inspection plan: where the robot must stand to see each target, and the route there");
  args.cmd = cmd;
  cmd->add_option("--map", args.map_path, "crafted map (PCD/PLY), map frame")->required();
  cmd->add_option("--costmap", args.costmap_dir, "costmap folder of `hylo traversability`")
      ->required();
  cmd->add_option("--targets", args.targets_path,
                  "targets, CSV (id,x,y,z[,min_range_m,max_range_m,size_x,size_y,size_z,"
                  "view_azimuth_deg,view_tolerance_deg]) or YAML, map frame")
      ->required();
  cmd->add_option("--out", args.out_dir, "output folder")->required();
  cmd->add_option("--start", args.start,
                  "where the route starts, \"x y\" in the map frame, m (default: the map "
                  "frame's origin, where SLAM started)");
  cmd->add_option("--config", args.config_path,
                  "run configuration whose `inspection:` section sets the options (the flags "
                  "below override it)");
  const inspection::InspectionOptions d;
  cmd->add_option("--camera-height", args.camera_height_m,
                  WithDefault("camera above the ground, m", d.visibility.camera_height_m));
  cmd->add_option("--min-range", args.min_range_m,
                  WithDefault("default camera-to-target range, m", d.visibility.min_range_m));
  cmd->add_option("--max-range", args.max_range_m,
                  WithDefault("default camera-to-target range, m", d.visibility.max_range_m));
  cmd->add_option("--clearance", args.clearance_m,
                  WithDefault("sight lines keep this far from map points, m",
                              d.visibility.occupancy.clearance_m));
  cmd->add_option("--voxel", args.voxel_m,
                  WithDefault("voxel edge of the map's occupancy, m",
                              d.visibility.occupancy.voxel_size_m));
  cmd->add_option("--robot-radius", args.robot_radius_m,
                  WithDefault("the robot's centre keeps this far from lethal cells, m",
                              d.search.robot_radius_m));
  cmd->add_flag("--no-return", args.no_return, "end the route at the last viewpoint");
  cmd->add_option("--json", args.json_path, "also write the summary here");
  cmd->callback([] { Run(args); });
}

}  // namespace hylo::cli
