// `hylo inspect --map CRAFTED --costmap DIR --targets FILE --out DIR`: where the robot must
// stand to see each target (sight lines through the crafted map) and the route there on the
// costmap; writes plan.csv, route.csv, visibility/, plan.png and summary.json
// (hylo/io/inspection_io.h).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"
#include "hylo/common/local_origin.h"
#include "hylo/config/run_config.h"
#include "hylo/inspection/planner.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/costmap_io.h"
#include "hylo/io/inspection_io.h"
#include "hylo/io/progress.h"
#include "hylo/io/targets_io.h"
#include "hylo/io/text.h"

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
  inspection::InspectionOptions o =
      a.config_path.empty() ? inspection::InspectionOptions()
                            : config::LoadRunConfig(a.config_path).inspection;
  const auto given = [&](const char* flag) { return a.cmd->count(flag) > 0; };
  inspection::VisibilityOptions& v = o.visibility;
  if (given("--camera-height")) v.camera_height_m = a.camera_height_m;
  if (given("--min-range")) v.min_range_m = a.min_range_m;
  if (given("--max-range")) v.max_range_m = a.max_range_m;
  if (given("--clearance")) v.occupancy.clearance_m = a.clearance_m;
  if (given("--voxel")) v.occupancy.voxel_size_m = a.voxel_m;
  if (given("--robot-radius")) o.search.robot_radius_m = a.robot_radius_m;
  if (a.no_return) o.tour.return_to_start = false;
  std::string why;
  if (!o.IsValid(&why)) throw std::invalid_argument("options: " + why);
  return o;
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
  std::fprintf(stderr, "reading costmap %s\n", args.costmap_dir.c_str());
  const io::CostmapLayers costmap = io::ReadCostmapLayers(args.costmap_dir);
  const Eigen::Vector3d origin = costmap.grid.geometry().origin_world;
  std::vector<inspection::Target> targets = io::ReadTargets(args.targets_path);
  for (inspection::Target& t : targets) t.position -= origin;
  std::fprintf(stderr, "reading map %s\n", args.map_path.c_str());
  const io::CloudFile map = io::ReadCloud(args.map_path);
  if (map.positions.empty()) throw std::runtime_error(args.map_path + ": the map has no point");
  const PointCloud map_local = ToLocal(map.positions, origin);
  std::fprintf(stderr, "planning %zu targets on %d x %d cells, %zu map points\n", targets.size(),
               costmap.grid.geometry().width, costmap.grid.geometry().height, map_local.size());
  std::unique_ptr<io::Progress> progress;
  std::string stage;
  const auto on_progress = [&](const std::string& name, std::size_t done, std::size_t total) {
    if (name != stage) {
      progress = std::make_unique<io::Progress>(name, total);
      stage = name;
    }
    progress->Update(done);
  };
  inspection::InspectionPlan plan;
  try {
    plan = inspection::PlanInspection(map_local, costmap.grid, costmap.classes, targets,
                                      start_map - origin.head<2>(), options, on_progress);
  } catch (const inspection::StartNotPassable& e) {
    char where[96];
    std::snprintf(where, sizeof(where), "start (%.3f, %.3f) in the map frame: ", start_map.x(),
                  start_map.y());
    throw std::runtime_error(where + std::string(e.what()) + " (give --start \"x y\")");
  }
  progress.reset();
  io::Json summary = io::InspectionPlanJson(plan, targets, costmap.grid.geometry(), options);
  summary["map"] = args.map_path;
  summary["costmap"] = args.costmap_dir;
  summary["targets_file"] = args.targets_path;
  const std::vector<std::string> files =
      io::WriteInspectionFiles(args.out_dir, plan, targets, costmap, summary);
  PrintPlan(plan, targets);
  std::printf("wrote %zu files to %s\n", files.size(), args.out_dir.c_str());
  if (!args.json_path.empty()) {
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
