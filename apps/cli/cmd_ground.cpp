// `hylo ground --in CLOUD --out-ground G --out-objects O`: cloth simulation ground filter
// (Zhang et al. 2016) and a JSON summary.
#include <cstdio>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/progress.h"
#include "hylo/terrain/cloth_filter.h"

namespace hylo::cli {
namespace {

struct GroundArgs {
  std::string in_path, ground_path, objects_path, json_path;
  terrain::ClothFilterOptions options;
  bool no_slope_smoothing = false;
  bool vertical_distance = false;
  std::string hole_fill = "mean";  ///< --hole-fill, see HoleFillByName
};

// CLI names of terrain::ClothHoleFill.
const std::map<std::string, terrain::ClothHoleFill>& HoleFillByName() {
  static const std::map<std::string, terrain::ClothHoleFill> names = {
      {"mean", terrain::ClothHoleFill::kNeighbourMean},
      {"nearest", terrain::ClothHoleFill::kNearest},
      {"reference", terrain::ClothHoleFill::kReferenceScanline}};
  return names;
}

io::Json SummaryJson(const GroundArgs& args, const terrain::ClothFilterResult& r, double seconds) {
  const terrain::ClothFilterOptions& o = args.options;
  io::Json j = io::Json::object();
  j["in"] = args.in_path;
  j["out_ground"] = args.ground_path;
  j["out_objects"] = args.objects_path;
  io::Json& opt = j["options"];
  opt["cloth_resolution_m"] = o.cloth_resolution_m;
  opt["rigidness"] = o.rigidness;
  opt["time_step"] = o.time_step;
  opt["max_iterations"] = o.max_iterations;
  opt["class_threshold_m"] = o.class_threshold_m;
  opt["class_distance_along_normal"] = o.class_distance_along_normal;
  opt["slope_smoothing"] = o.slope_smoothing;
  opt["slope_height_threshold_m"] = o.slope_height_threshold_m;
  opt["slope_max_cloth_gap_m"] = o.slope_max_cloth_gap_m;  // null when infinite (no test)
  opt["slope_min_region_particles"] = o.slope_min_region_particles;
  opt["convergence_threshold_m"] = o.convergence_threshold_m;
  opt["hole_fill"] = args.hole_fill;
  opt["low_outlier_depth_m"] = o.low_outlier_depth_m;
  opt["low_outlier_cell_m"] = o.low_outlier_cell_m;
  opt["low_outlier_min_support"] = o.low_outlier_min_support;
  opt["low_outlier_max_fraction"] = o.low_outlier_max_fraction;
  opt["gravity"] = o.gravity;
  io::Json& p = j["points"];
  p["ground"] = r.num_ground;
  p["objects"] = r.num_objects;
  p["non_finite"] = r.num_invalid;
  p["low_outliers"] = r.num_low_outliers;
  io::Json& c = j["cloth"];
  c["cols"] = r.cloth_cols;
  c["rows"] = r.cloth_rows;
  c["iterations"] = r.iterations;
  c["converged"] = r.converged;
  c["last_max_displacement_m"] = r.last_max_displacement_m;
  c["hole_particles"] = r.num_hole_particles;
  c["pinned_by_slope"] = r.num_pinned_by_slope;
  j["origin_world"] = io::Json::array({r.origin_world.x(), r.origin_world.y(), r.origin_world.z()});
  j["seconds"] = seconds;
  return j;
}

// The points of `cloud` labelled `label`, with their attributes.
io::CloudFile Select(const io::CloudFile& cloud, const terrain::ClothFilterResult& r,
                     terrain::GroundLabel label) {
  io::CloudFile out;
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    if (r.labels[i] != label) continue;
    out.positions.push_back(cloud.positions[i]);
    if (!cloud.intensity.empty()) out.intensity.push_back(cloud.intensity[i]);
    if (!cloud.normals.empty()) out.normals.push_back(cloud.normals[i]);
    if (!cloud.labels.empty()) out.labels.push_back(cloud.labels[i]);
  }
  return out;
}

void RunGround(GroundArgs& args) {
  args.options.slope_smoothing = !args.no_slope_smoothing;
  args.options.class_distance_along_normal = !args.vertical_distance;
  args.options.hole_fill = HoleFillByName().at(args.hole_fill);  // CLI checked the name
  std::string why;
  if (!args.options.IsValid(&why)) throw std::invalid_argument(why);
  std::fprintf(stderr, "reading %s\n", args.in_path.c_str());
  const io::CloudFile cloud = io::ReadCloud(args.in_path);
  auto progress = std::make_unique<io::Progress>(
      "cloth simulation", static_cast<std::size_t>(args.options.max_iterations));
  const terrain::ClothFilterResult result = terrain::FilterGround(
      cloud.positions, args.options,
      [&progress](int iteration, int) { progress->Update(static_cast<std::size_t>(iteration)); });
  const double seconds = progress->ElapsedSeconds();
  progress.reset();
  if (!result.ok) throw std::runtime_error(args.in_path + ": " + result.message);
  std::fprintf(stderr, "%s\n", result.message.c_str());
  io::WriteCloud(args.ground_path, Select(cloud, result, terrain::GroundLabel::kGround));
  io::WriteCloud(args.objects_path, Select(cloud, result, terrain::GroundLabel::kObject));
  std::fprintf(stderr, "wrote %s and %s\n", args.ground_path.c_str(), args.objects_path.c_str());
  io::Json summary = SummaryJson(args, result, seconds);
  summary["points"]["non_finite"] = result.num_invalid + cloud.dropped_non_finite;
  MaybeWriteJson(args.json_path, summary);
}

}  // namespace

void AddGroundCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "ground", "Split a cloud into ground and objects with a cloth simulation filter (CSF)");
  static GroundArgs args;
  terrain::ClothFilterOptions& o = args.options;
  cmd->add_option("--in", args.in_path, "cloud (PCD/PLY), may be in UTM coordinates")->required();
  cmd->add_option("--out-ground", args.ground_path, "ground points to write")->required();
  cmd->add_option("--out-objects", args.objects_path, "object points to write")->required();
  cmd->add_option("--resolution", o.cloth_resolution_m, "cloth grid resolution (GR), m")
      ->capture_default_str();
  cmd->add_option("--rigidness", o.rigidness, "cloth rigidness (RI): 1 steep .. 3 flat")
      ->capture_default_str();
  cmd->add_option("--time-step", o.time_step, "simulation time step (dT)")->capture_default_str();
  cmd->add_option("--iterations", o.max_iterations, "maximum simulation steps")
      ->capture_default_str();
  cmd->add_option("--threshold", o.class_threshold_m, "ground if closer to the cloth, m (hcc)")
      ->capture_default_str();
  cmd->add_flag("--vertical-distance", args.vertical_distance,
                "classify by the vertical gap to the cloth (the original CSF code) instead of "
                "the distance to the cloth surface");
  cmd->add_flag("--no-slope-smoothing", args.no_slope_smoothing,
                "skip the steep-slope post-processing (ST)");
  cmd->add_option("--slope-threshold", o.slope_height_threshold_m,
                  "post-processing height continuity threshold, m")
      ->capture_default_str();
  cmd->add_option("--slope-max-gap", o.slope_max_cloth_gap_m,
                  "post-processing pins particles only where the cloth is closer than this to "
                  "the surface (inf = no test, as the original CSF code), m")
      ->capture_default_str();
  cmd->add_option("--low-outlier-depth", o.low_outlier_depth_m,
                  "points this far below nearly all neighbours do not hold the cloth up, m "
                  "(0 = off)")
      ->capture_default_str();
  cmd->add_option("--low-outlier-fraction", o.low_outlier_max_fraction,
                  "a point is also a low outlier when fewer than this fraction of the points "
                  "around it reach its level (0 = by count only)")
      ->capture_default_str();
  std::vector<std::string> fill_names;
  for (const auto& [name, fill] : HoleFillByName()) fill_names.push_back(name);
  cmd->add_option("--hole-fill", args.hole_fill,
                  "height under particles without a point: mean (of known neighbours), nearest "
                  "(nearest measured particle, the paper's nearest point; suits a cloth finer "
                  "than the point spacing), reference (along rows/columns as the original CSF "
                  "code)")
      ->check(CLI::IsMember(fill_names))
      ->capture_default_str();
  cmd->add_option("--gravity", o.gravity,
                  "cloth gravity per step^2 (the original code's build used 0.2 dT^2)")
      ->capture_default_str();
  cmd->add_option("--json", args.json_path, "write a JSON summary here");
  cmd->callback([] { RunGround(args); });
}

}  // namespace hylo::cli
