// `hylo traversability --ground G [--objects O] --out DIR`: ground (+ object) clouds -> grid
// map layers -> traversability costmap (map_server PGM + YAML, coloured PNG, ASCII grids) and
// a JSON summary.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "commands.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/costmap_io.h"
#include "hylo/io/progress.h"
#include "hylo/terrain/traversability.h"

namespace hylo::cli {
namespace {

struct TraversabilityArgs {
  std::string ground_path, objects_path, out_dir, json_path;
  terrain::TraversabilityOptions options;
  bool no_cell_grade = false;
  bool estimate_edge_cells = false;
};

io::Json OptionsJson(const terrain::TraversabilityOptions& o) {
  io::Json j = io::Json::object();
  j["resolution_m"] = o.resolution_m;
  j["max_hole_size_m"] = o.elevation.max_hole_size_m;
  j["normal_radius_m"] = o.surface.normal_radius_m;
  j["fallback_radius_m"] = o.surface.fallback_radius_m;
  j["scale_consistency_sigmas"] = o.surface.scale_consistency_sigmas;
  j["unknown_at_data_edge"] = o.surface.unknown_at_data_edge;
  j["step_radius_m"] = o.surface.step_radius_m;
  j["max_slope_deg"] = o.cost.max_slope_deg;
  j["max_step_m"] = o.cost.max_step_m;
  j["max_roughness_m"] = o.cost.max_roughness_m;
  j["lethal_on_cell_grade"] = o.cost.lethal_on_cell_grade;
  j["free_cost_max"] = o.cost.free_cost_max;
  j["obstacle_min_height_m"] = o.cost.obstacle_min_height_m;
  j["obstacle_max_height_m"] = o.cost.obstacle_max_height_m;
  return j;
}

io::Json SummaryJson(const TraversabilityArgs& args, const terrain::TraversabilityMap& map) {
  const terrain::GridGeometry& g = map.grid.geometry();
  const terrain::TraversabilitySummary& s = map.summary;
  io::Json j = io::Json::object();
  j["ground"] = args.ground_path;
  j["objects"] = args.objects_path;
  j["options"] = OptionsJson(args.options);
  j["origin_world"] = io::Json::array({g.origin_world.x(), g.origin_world.y(), g.origin_world.z()});
  j["corner_world"] = io::Json::array({g.CornerWorld().x(), g.CornerWorld().y()});
  j["resolution_m"] = g.resolution_m;
  j["width"] = g.width;
  j["height"] = g.height;
  io::Json& cells = j["cells"];
  for (int c = 0; c < terrain::kNumCellClasses; ++c) {
    cells[terrain::CellClassName(static_cast<terrain::CellClass>(c))] = s.cells_per_class[c];
  }
  cells["measured"] = s.elevation.measured_cells;
  cells["hole_filled"] = s.elevation.filled_cells;
  cells["holes_too_large"] = s.elevation.holes_too_large;
  cells["without_plane"] = s.surface.cells_too_few_points + s.surface.cells_degenerate;
  cells["plane_from_fallback_radius"] = s.surface.cells_fallback;
  cells["normal_from_finer_block"] = s.surface.cells_finer_scale;
  cells["unknown_at_data_edge"] = s.surface.cells_at_data_edge;
  cells["lethal_from_obstacles"] = s.obstacles.lethal_cells;
  j["surface_noise_m"] = s.surface.noise_m;
  io::Json& slope = j["slope_deg"];
  slope["cells"] = s.slope.cells;
  slope["mean"] = s.slope.mean_deg;
  slope["median"] = s.slope.median_deg;
  slope["p95"] = s.slope.p95_deg;
  slope["max"] = s.slope.max_deg;
  io::Json& points = j["points"];
  points["ground"] = s.ground_points;
  points["ground_non_finite"] = s.ground_points_skipped;
  points["objects"] = s.object_points;
  points["objects_in_obstacle_band"] = s.obstacles.points_in_band;
  points["objects_below_band"] = s.obstacles.points_below_band;
  points["objects_above_band"] = s.obstacles.points_above_band;
  points["objects_without_ground"] = s.obstacles.points_without_ground;
  return j;
}

std::vector<Eigen::Vector3d> ReadPositions(const std::string& path, const char* what) {
  std::fprintf(stderr, "reading %s cloud %s\n", what, path.c_str());
  io::CloudFile cloud = io::ReadCloud(path);
  if (cloud.dropped_non_finite > 0) {
    std::fprintf(stderr, "  %zu non-finite points dropped\n", cloud.dropped_non_finite);
  }
  return std::move(cloud.positions);
}

void Run(const TraversabilityArgs& args) {
  std::string why;
  if (!args.options.IsValid(&why)) throw std::invalid_argument("options: " + why);
  const auto ground = ReadPositions(args.ground_path, "ground");
  if (ground.empty()) throw std::runtime_error(args.ground_path + ": the ground cloud is empty");
  const auto objects = args.objects_path.empty() ? std::vector<Eigen::Vector3d>{}
                                                 : ReadPositions(args.objects_path, "object");
  io::Progress progress("traversability", 5);
  const terrain::TraversabilityMap map = terrain::ComputeTraversability(
      ground, objects, args.options,
      [&](const std::string&, int index, int) { progress.Update(index); });
  progress.Update(5);
  progress.Finish();
  const std::vector<std::string> files = io::WriteTraversabilityFiles(args.out_dir, map);
  io::Json summary = SummaryJson(args, map);
  for (const std::string& f : files) summary["outputs"].push_back(f);
  const auto& n = map.summary.cells_per_class;
  std::printf("grid %d x %d at %.3f m, corner (%.3f, %.3f)\n", map.grid.geometry().width,
              map.grid.geometry().height, map.grid.geometry().resolution_m,
              map.grid.geometry().CornerWorld().x(), map.grid.geometry().CornerWorld().y());
  std::printf("cells: free %zu, cost %zu, lethal %zu (obstacles %zu), unknown %zu (%zu at a data "
              "edge)\n", n[1], n[2], n[3], map.summary.obstacles.lethal_cells, n[0],
              map.summary.surface.cells_at_data_edge);
  std::printf("slope: mean %.2f, median %.2f, p95 %.2f, max %.2f deg over %zu cells\n",
              map.summary.slope.mean_deg, map.summary.slope.median_deg, map.summary.slope.p95_deg,
              map.summary.slope.max_deg, map.summary.slope.cells);
  std::printf("wrote %zu files to %s\n", files.size(), args.out_dir.c_str());
  MaybeWriteJson(args.json_path, summary);
}

}  // namespace

void AddTraversabilityCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "traversability", "Ground (+ object) cloud -> grid map layers -> traversability costmap");
  static TraversabilityArgs args;
  terrain::CostOptions& cost = args.options.cost;
  cmd->add_option("--ground", args.ground_path, "ground cloud (PCD/PLY/LAS)")->required();
  cmd->add_option("--objects", args.objects_path, "object (non-ground) cloud: obstacles");
  cmd->add_option("--out", args.out_dir, "output folder")->required();
  cmd->add_option("--resolution", args.options.resolution_m, "grid cell edge, m")
      ->capture_default_str();
  cmd->add_option("--max-slope", cost.max_slope_deg, "vehicle limit, deg")->capture_default_str();
  cmd->add_option("--max-step", cost.max_step_m, "vehicle limit, m")->capture_default_str();
  cmd->add_option("--max-roughness", cost.max_roughness_m, "vehicle limit, m")
      ->capture_default_str();
  cmd->add_flag("--no-cell-grade", args.no_cell_grade,
                "do not mark cells lethal from the cell-scale elevation gradient (only the "
                "footprint slope, step and roughness)");
  cmd->add_option("--scale-sigmas", args.options.surface.scale_consistency_sigmas,
                  "adaptive scale: a block of cells replaces the footprint plane when they differ "
                  "by more than this many tilt standard deviations (0: always the footprint)")
      ->capture_default_str();
  cmd->add_flag("--estimate-edge-cells", args.estimate_edge_cells,
                "also give a slope to cells next to a cell without elevation (default: "
                "unknown, the unseen neighbour may hide a drop)");
  cmd->add_option("--max-hole", args.options.elevation.max_hole_size_m,
                  "fill enclosed holes up to this width, m (0: none)")
      ->capture_default_str();
  cmd->add_option("--json", args.json_path, "write a JSON summary here");
  cmd->callback([] {
    args.options.cost.lethal_on_cell_grade = !args.no_cell_grade;
    args.options.surface.unknown_at_data_edge = !args.estimate_edge_cells;
    Run(args);
  });
}

}  // namespace hylo::cli
