// The offline chain's figures on the simulated substation: crafting thickness and time,
// ground labels, traversability slope, all against the simulator's truth. Figures are
// printed and written as JSON; tests/sim/site_mapping_test.cpp checks the --quick settings.
//
//   hylo_site_mapping_eval [--quick] [--seed N] [--duration S] [--stride N]
//                          [--lidar vlp16|rs16] [--resolution M] [--out DIR] [--json PATH]
//                          [--cells]   (per-cell CSV tables of the slope error in --out)
//                          [--only-craft | --only-slope] [--mls-radius M] [--order N]
//                          [--small-radius M] [--support-voxel M]  (CraftOptions: small radius
//                          0 = single scale; support voxel >= sampling voxel = sampled points only)
//                          [--ground-method smrf|csf]  (smrf: the demo's, ForRobotMaps; csf:
//                          the cloth filter with the paper's defaults, the chain's before)
// Full: the simulator's default session A (180 s, 0.2 deg columns), every scan. --quick: the
// simulator's coarse settings (SimulationOptions::Fast: 1 deg columns, 0.4 m terrain) for 20 s.

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "hylo/io/json.h"
#include "hylo/sim_io/session_writer.h"
#include "site_mapping_eval_core.h"

namespace {

using hylo::io::Json;
using hylo::site_eval::GroundFigures;
using hylo::site_eval::SiteEvalOptions;
using hylo::site_eval::SiteFigures;
using hylo::site_eval::SlopeFigures;
using hylo::site_eval::Thickness;

Json ThicknessJson(const Thickness& t) {
  Json j = Json::object();
  j["points_measured"] = t.points;
  j["rms_m"] = t.rms_m;
  j["rms_ground_m"] = t.rms_ground_m;
  j["rms_object_m"] = t.rms_object_m;
  j["rms_thin_object_m"] = t.rms_thin_m;
  j["rms_thick_box_m"] = t.rms_thick_box_m;
  j["rms_thick_cylinder_m"] = t.rms_thick_cylinder_m;
  j["fraction_thin_object"] = t.fraction_thin;
  j["fraction_ground"] = t.fraction_ground;
  j["p95_m"] = t.p95_m;
  j["fraction_beyond_10cm"] = t.beyond_10cm;
  return j;
}

Json SlopeJson(const SlopeFigures& s) {
  Json j = Json::object();
  j["measured_cells"] = s.measured_cells;
  j["cells_compared"] = s.slope.cells;
  j["coverage"] = s.Coverage();
  j["cells_unknown_at_data_edge"] = s.cells_at_data_edge;
  j["cells_normal_from_finer_block"] = s.cells_finer_scale;
  j["noise_m"] = s.noise_m;
  j["slope_rmse_deg"] = s.slope.rmse;
  j["slope_bias_deg"] = s.slope.mean_error;
  j["slope_max_abs_error_deg"] = s.slope.max_abs_error;
  j["steep_cells"] = s.steep.steep_cells;
  j["steep_marked_lethal"] = s.steep.marked_lethal;
  j["steep_fraction_marked"] = s.steep.fraction_marked;
  j["steep_unknown"] = s.steep.steep_unknown;
  j["slope_rmse_vs_footprint_truth_deg"] = s.slope_footprint.rmse;
  j["seconds"] = s.seconds;
  return j;
}

Json FiguresJson(const SiteEvalOptions& o, const SiteFigures& f) {
  Json j = Json::object();
  j["simulation"] = hylo::sim::OptionsToJson(o.sim);
  Json& m = j["map"];
  m["scan_stride"] = o.scan_stride;
  m["scans"] = f.map.scan_begin.size();
  m["points"] = f.map.points_map.size();
  m["simulate_seconds"] = f.map.simulate_seconds;
  Json& c = j["craft"];
  c["voxel_size_m"] = o.craft.voxel_size_m;
  c["mls_search_radius_m"] = o.craft.mls_search_radius_m;
  c["polynomial_order"] = o.craft.polynomial_order;
  c["mls_support_voxel_m"] = o.craft.mls_support_voxel_m;
  c["mls_small_radius_m"] = o.craft.mls_small_radius_m;
  c["scale_consistency_sigmas"] = o.craft.scale_consistency_sigmas;
  c["raw"] = ThicknessJson(f.craft.raw);
  c["sampled"] = ThicknessJson(f.craft.sampled);
  c["crafted"] = ThicknessJson(f.craft.crafted);
  c["sampled_points"] = f.craft.sampled_points;
  c["crafted_points"] = f.craft.crafted_points;
  c["dropped_by_mls"] = f.craft.sampled_points - f.craft.crafted_points;
  c["mls_support_points"] = f.craft.support_points;
  c["small_scale_points"] = f.craft.small_scale_points;

  c["thickness_ratio"] = f.craft.ThicknessRatio();
  c["thickness_ratio_sampled_over_crafted"] = f.craft.sampled.rms_m / f.craft.crafted.rms_m;
  c["seconds_whole_map"] = f.craft.seconds;
  c["timing_points"] = f.craft.timing_points;
  c["seconds_1_thread"] = f.craft.seconds_1_thread;
  c["seconds_2_threads"] = f.craft.seconds_2_threads;
  const GroundFigures& g = f.ground;
  Json& gj = j["ground"];
  gj["voxel_m"] = o.ground_voxel_m;
  gj["points"] = f.ground_filter_points;
  gj["true_ground"] = g.ground_as_ground + g.ground_as_object;
  gj["true_objects"] = g.object_as_ground + g.object_as_object;
  gj["type_i"] = g.TypeI();
  gj["type_ii"] = g.TypeII();
  gj["total_error"] = g.Total();
  gj["kappa"] = g.Kappa();
  gj["method"] = g.method;
  gj["seconds"] = g.seconds;
  Json& t = j["traversability"];
  t["resolution_m"] = o.traversability.resolution_m;
  t["max_slope_deg"] = o.traversability.cost.max_slope_deg;
  t["from_ground_filter"] = SlopeJson(f.slope_filter);
  t["from_true_ground"] = SlopeJson(f.slope_truth);
  t["from_true_ground_edge_cells_estimated"] = SlopeJson(f.slope_truth_all_cells);
  return j;
}

void PrintThickness(const char* name, const Thickness& t) {
  std::printf("  %-26s %9zu %9.4f %9.4f %9.4f %9.4f %9.4f %8.3f%%\n", name, t.points, t.rms_m,
              t.rms_ground_m, t.rms_object_m, t.rms_thin_m, t.p95_m, 100 * t.beyond_10cm);
}

void PrintSlope(const char* name, const SlopeFigures& s) {
  std::printf("  %-26s %8zu %8zu %7.2f%% %8.3f %8.3f %8zu %8.2f%% %8zu\n", name, s.measured_cells,
              s.slope.cells, 100 * s.Coverage(), s.slope.rmse, s.slope.mean_error,
              s.steep.steep_cells, 100 * s.steep.fraction_marked, s.steep.steep_unknown);
}

void PrintFigures(const SiteEvalOptions& o, const SiteFigures& f) {
  std::printf("\nmap: %zu scans (stride %d), %zu points, simulated + registered in %.1f s\n",
              f.map.scan_begin.size(), o.scan_stride, f.map.points_map.size(),
              f.map.simulate_seconds);
  std::printf("\n1. crafting (voxel %.3f m, MLS radius %.3f m, order %d): distance to true surface\n",
              o.craft.voxel_size_m, o.craft.mls_search_radius_m, o.craft.polynomial_order);
  std::printf("  %-26s %9s %9s %9s %9s %9s %9s %9s\n", "cloud", "measured", "rms_m", "ground_m",
              "object_m", "thin_m", "p95_m", ">10cm");
  PrintThickness("raw accumulated", f.craft.raw);
  PrintThickness("uniform sampling only", f.craft.sampled);
  PrintThickness("crafted (sampling + MLS)", f.craft.crafted);
  std::printf("  points nearest the ground %.1f%%, a thin (< 0.1 m) primitive %.1f%% (raw map)\n",
              100 * f.craft.raw.fraction_ground, 100 * f.craft.raw.fraction_thin);
  std::printf("  thicker primitives, rms raw -> crafted: boxes %.4f -> %.4f m, cylinders %.4f -> "
              "%.4f m\n", f.craft.raw.rms_thick_box_m, f.craft.crafted.rms_thick_box_m,
              f.craft.raw.rms_thick_cylinder_m, f.craft.crafted.rms_thick_cylinder_m);
  std::printf("  thickness ratio raw/crafted %.2f (target >= 2), sampled/crafted %.2f; "
              "%zu crafted points in %.1f s\n",
              f.craft.ThicknessRatio(), f.craft.sampled.rms_m / f.craft.crafted.rms_m,
              f.craft.crafted_points, f.craft.seconds);
  std::printf("  MLS input %zu points: %zu dropped (too few neighbours: absent from the map "
              "and from the figures)\n",
              f.craft.sampled_points, f.craft.sampled_points - f.craft.crafted_points);
  std::printf("  MLS fits on %zu points (support voxel %.4f m); %zu crafted points took the "
              "small radius %.3f m\n", f.craft.support_points, o.craft.mls_support_voxel_m,
              f.craft.small_scale_points, o.craft.mls_small_radius_m);
  std::printf("  time on %zu points: 1 thread %.2f s, 2 threads %.2f s (shared machine)\n",
              f.craft.timing_points, f.craft.seconds_1_thread, f.craft.seconds_2_threads);
  const GroundFigures& g = f.ground;
  std::printf("\n2. ground (%s, %zu points, one per %.2f m voxel, hit-surface truth)\n",
              g.method.c_str(), f.ground_filter_points, o.ground_voxel_m);
  std::printf("  type I %.2f%%  type II %.2f%%  total %.2f%%  kappa %.2f%%  (%.1f s)\n",
              100 * g.TypeI(), 100 * g.TypeII(), 100 * g.Total(), 100 * g.Kappa(),
              g.seconds);
  std::printf("\n3. traversability (%.2f m cells, limit %.1f deg) vs site_slope.txt\n",
              o.traversability.resolution_m, o.traversability.cost.max_slope_deg);
  std::printf("  %-26s %8s %8s %8s %8s %8s %8s %9s %8s\n", "ground from", "measured",
              "compared", "coverage", "rmse_deg", "bias_deg", "steep", "marked", "steep_unk");
  PrintSlope("ground filter (the chain)", f.slope_filter);
  PrintSlope("true labels", f.slope_truth);
  PrintSlope("true labels, edges estimated", f.slope_truth_all_cells);
  std::printf("  (compared: cells with ground points and a slope; coverage = compared / measured;\n"
              "   true labels: %zu cells unknown at a data edge, %zu normals from a block finer\n"
              "   than the footprint, height noise %.4f m)\n",
              f.slope_truth.cells_at_data_edge, f.slope_truth.cells_finer_scale,
              f.slope_truth.noise_m);
}

bool ParseArgs(int argc, char** argv, SiteEvalOptions* o, std::string* json_path) {
  bool quick = false;
  double duration_s = -1, resolution_m = -1, mls_radius_m = -1, small_radius_m = -1;
  double support_voxel_m = -1;
  int stride = 0, order = -1;
  std::string only;
  std::string lidar;
  std::string ground_method;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--quick") quick = true;
    else if (a == "--seed" && has_value) o->sim.seed = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--duration" && has_value) duration_s = std::atof(argv[++i]);
    else if (a == "--stride" && has_value) stride = std::atoi(argv[++i]);
    else if (a == "--lidar" && has_value) lidar = argv[++i];
    else if (a == "--resolution" && has_value) resolution_m = std::atof(argv[++i]);
    else if (a == "--out" && has_value) o->out_dir = argv[++i];
    else if (a == "--json" && has_value) *json_path = argv[++i];
    else if (a == "--cells") o->write_cell_tables = true;
    else if (a == "--only-craft") only = "craft";
    else if (a == "--only-slope") only = "slope";
    else if (a == "--mls-radius" && has_value) mls_radius_m = std::atof(argv[++i]);
    else if (a == "--order" && has_value) order = std::atoi(argv[++i]);
    else if (a == "--small-radius" && has_value) small_radius_m = std::atof(argv[++i]);
    else if (a == "--support-voxel" && has_value) support_voxel_m = std::atof(argv[++i]);
    else if (a == "--ground-method" && has_value) ground_method = argv[++i];
    else {
      std::fprintf(stderr, "unknown argument '%s'\n", a.c_str());
      return false;
    }
  }
  const uint64_t seed = o->sim.seed;
  const bool cells = o->write_cell_tables;
  if (quick) *o = hylo::site_eval::QuickOptions(o->out_dir);
  o->sim.seed = seed;
  o->write_cell_tables = cells;
  if (duration_s > 0) o->sim.duration_a_s = duration_s;
  if (stride != 0) o->scan_stride = stride;
  if (resolution_m > 0) o->traversability.resolution_m = resolution_m;
  if (mls_radius_m > 0) o->craft.mls_search_radius_m = mls_radius_m;
  if (order >= 0) o->craft.polynomial_order = order;
  if (small_radius_m >= 0) o->craft.mls_small_radius_m = small_radius_m;
  if (support_voxel_m >= 0) o->craft.mls_support_voxel_m = support_voxel_m;
  o->measure_craft = only != "slope";
  o->measure_ground_and_slope = only != "craft";
  if (!ground_method.empty() &&
      !hylo::terrain::ParseGroundMethod(ground_method, &o->ground.method)) {
    std::fprintf(stderr, "unknown ground method '%s' (smrf or csf)\n", ground_method.c_str());
    return false;
  }
  // The cloth filter as the chain ran it before SMRF: the paper's defaults.
  if (o->ground.method == hylo::terrain::GroundMethod::kCsf) o->ground.csf = {};
  if (!lidar.empty() && !hylo::sim::ParseLidarModel(lidar, &o->sim.lidar.model)) {
    std::fprintf(stderr, "unknown lidar '%s'\n", lidar.c_str());
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  SiteEvalOptions options;
  options.sim.seed = 1;
  options.out_dir = "site_mapping_eval_out";
  std::string json_path;
  if (!ParseArgs(argc, argv, &options, &json_path)) return 2;
  std::string why;
  if (!options.IsValid(&why)) {
    std::fprintf(stderr, "invalid options: %s\n", why.c_str());
    return 2;
  }
  std::printf("simulation options (seed %llu):\n%s\n",
              static_cast<unsigned long long>(options.sim.seed),
              hylo::sim::OptionsToJson(options.sim).dump().c_str());
  try {
    const SiteFigures figures = hylo::site_eval::EvaluateSite(options);
    PrintFigures(options, figures);
    if (!json_path.empty()) hylo::io::WriteJsonFile(json_path, FiguresJson(options, figures));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
