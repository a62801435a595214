// `hylo ground --in CLOUD --out-ground G --out-objects O [--method csf|smrf]`: ground / object
// split by the simple morphological filter (Pingel et al. 2013) or the cloth simulation
// filter (Zhang et al. 2016), and a JSON summary naming the method and its options. LAS
// outputs carry the split as ASPRS classes (ground 2).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"
#include "hylo/config/config_json.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/progress.h"
#include "hylo/io/text.h"
#include "hylo/terrain/ground_filter.h"

namespace hylo::cli {
namespace {

struct GroundArgs {
  std::string in_path, ground_path, objects_path, json_path;
  terrain::GroundFilterOptions options;
  std::string method = terrain::ToString(terrain::GroundFilterOptions().method);
  bool no_slope_smoothing = false;
  bool vertical_distance = false;
  std::string hole_fill = terrain::ToString(terrain::GroundFilterOptions().csf.hole_fill);
};

// What the back-end reports beyond the point counts.
io::Json StatsJson(const terrain::GroundFilterResult& r) {
  io::Json s = io::Json::object();
  if (r.method == terrain::GroundMethod::kCsf) {
    s["cols"] = r.csf.cloth_cols;
    s["rows"] = r.csf.cloth_rows;
    s["iterations"] = r.csf.iterations;
    s["converged"] = r.csf.converged;
    s["last_max_displacement_m"] = r.csf.last_max_displacement_m;
    s["hole_particles"] = r.csf.num_hole_particles;
    s["pinned_by_slope"] = r.csf.num_pinned_by_slope;
  } else {
    s["cols"] = r.smrf.grid_cols;
    s["rows"] = r.smrf.grid_rows;
    s["empty_cells"] = r.smrf.num_empty_cells;
    s["object_cells"] = r.smrf.num_object_cells;
    s["readmitted_cells"] = r.smrf.num_readmitted_cells;
    s["low_outlier_cells"] = r.smrf.num_low_outlier_cells;
  }
  return s;
}

io::Json SummaryJson(const GroundArgs& args, const terrain::GroundFilterResult& r,
                     double seconds) {
  io::Json j = io::Json::object();
  j["in"] = args.in_path;
  j["out_ground"] = args.ground_path;
  j["out_objects"] = args.objects_path;
  j["method"] = terrain::ToString(r.method);
  // The back-end's options as the configuration's ground section names them.
  j["options"] = r.method == terrain::GroundMethod::kCsf ? config::ToJson(args.options.csf)
                                                         : config::ToJson(args.options.smrf);
  io::Json& p = j["points"];
  p["ground"] = r.num_ground;
  p["objects"] = r.num_objects;
  p["non_finite"] = r.num_invalid;
  if (r.method == terrain::GroundMethod::kCsf) p["low_outliers"] = r.csf.num_low_outliers;
  j[r.method == terrain::GroundMethod::kCsf ? "cloth" : "grid"] = StatsJson(r);
  j["origin_world"] =
      io::Json::array({r.origin_world.x(), r.origin_world.y(), r.origin_world.z()});
  j["seconds"] = seconds;
  return j;
}

// The points of `cloud` labelled `label`, with their attributes.
io::CloudFile Select(const io::CloudFile& cloud, const terrain::GroundFilterResult& r,
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

// ASPRS classes a LAS output carries, so that survey software reads the split: ground points are
// class 2; object points keep their input class, except "ground" (2) and "never classified" (0),
// which become 1 ("unclassified": processed, not ground). Other formats keep the input labels.
constexpr int32_t kLasNeverClassified = 0, kLasUnclassified = 1, kLasGround = 2;

void ClassifyForLas(const std::string& path, terrain::GroundLabel label, io::CloudFile* cloud) {
  if (io::ToLower(std::filesystem::path(path).extension().string()) != ".las") return;
  if (label == terrain::GroundLabel::kGround) {
    cloud->labels.assign(cloud->positions.size(), kLasGround);
    return;
  }
  if (cloud->labels.empty()) cloud->labels.assign(cloud->positions.size(), kLasUnclassified);
  for (int32_t& c : cloud->labels) {
    if (c == kLasNeverClassified || c == kLasGround) c = kLasUnclassified;
  }
}

io::CloudFile Output(const std::string& path, const io::CloudFile& cloud,
                     const terrain::GroundFilterResult& r, terrain::GroundLabel label) {
  io::CloudFile out = Select(cloud, r, label);
  ClassifyForLas(path, label, &out);
  return out;
}

// Steps the progress line counts: cloth simulation steps, or SMRF's openings.
std::unique_ptr<io::Progress> MakeProgress(const terrain::GroundFilterOptions& o) {
  if (o.method == terrain::GroundMethod::kCsf) {
    return std::make_unique<io::Progress>("cloth simulation",
                                          static_cast<std::size_t>(o.csf.max_iterations));
  }
  const double openings = std::ceil(o.smrf.max_window_m / o.smrf.cell_m - 1e-9);
  return std::make_unique<io::Progress>("SMRF openings", static_cast<std::size_t>(openings));
}

void RunGround(GroundArgs& args) {
  terrain::GroundFilterOptions& o = args.options;
  terrain::ParseGroundMethod(args.method, &o.method);  // CLI checked the name
  o.csf.slope_smoothing = !args.no_slope_smoothing;
  o.csf.class_distance_along_normal = !args.vertical_distance;
  terrain::ParseClothHoleFill(args.hole_fill, &o.csf.hole_fill);  // CLI checked the name
  std::string why;
  if (!o.IsValid(&why)) throw std::invalid_argument(why);
  std::fprintf(stderr, "reading %s\n", args.in_path.c_str());
  const io::CloudFile cloud = io::ReadCloud(args.in_path);
  std::unique_ptr<io::Progress> progress = MakeProgress(o);
  const terrain::GroundFilterResult result = terrain::ExtractGround(
      cloud.positions, o,
      [&progress](int step, int) { progress->Update(static_cast<std::size_t>(step)); });
  const double seconds = progress->ElapsedSeconds();
  progress.reset();
  if (!result.ok) throw std::runtime_error(args.in_path + ": " + result.message);
  std::fprintf(stderr, "%s: %s\n", terrain::ToString(result.method).c_str(), result.message.c_str());
  io::WriteCloud(args.ground_path,
                 Output(args.ground_path, cloud, result, terrain::GroundLabel::kGround));
  io::WriteCloud(args.objects_path,
                 Output(args.objects_path, cloud, result, terrain::GroundLabel::kObject));
  std::fprintf(stderr, "wrote %s and %s\n", args.ground_path.c_str(), args.objects_path.c_str());
  io::Json summary = SummaryJson(args, result, seconds);
  summary["points"]["non_finite"] = result.num_invalid + cloud.dropped_non_finite;
  MaybeWriteJson(args.json_path, summary);
}

void AddCsfOptions(CLI::App* cmd, GroundArgs& args) {
  const char* group = "Cloth simulation (--method csf)";
  terrain::ClothFilterOptions& o = args.options.csf;
  cmd->add_option("--resolution", o.cloth_resolution_m, "cloth grid resolution (GR), m")
      ->capture_default_str()->group(group);
  cmd->add_option("--rigidness", o.rigidness,
                  "cloth rigidness (RI): the paper's 1 steep .. 3 flat; stiffer up to 10")
      ->capture_default_str()->group(group);
  cmd->add_option("--time-step", o.time_step, "simulation time step (dT)")
      ->capture_default_str()->group(group);
  cmd->add_option("--iterations", o.max_iterations, "maximum simulation steps")
      ->capture_default_str()->group(group);
  cmd->add_option("--threshold", o.class_threshold_m, "ground if closer to the cloth, m (hcc)")
      ->capture_default_str()->group(group);
  cmd->add_flag("--vertical-distance", args.vertical_distance,
                "classify by the vertical gap to the cloth (the original CSF code) instead of "
                "the distance to the cloth surface")->group(group);
  cmd->add_flag("--no-slope-smoothing", args.no_slope_smoothing,
                "skip the steep-slope post-processing (ST)")->group(group);
  cmd->add_option("--slope-threshold", o.slope_height_threshold_m,
                  "post-processing height continuity threshold, m")
      ->capture_default_str()->group(group);
  cmd->add_option("--slope-max-gap", o.slope_max_cloth_gap_m,
                  "post-processing pins particles only where the cloth is closer than this to "
                  "the surface (inf = no test, as the original CSF code), m")
      ->capture_default_str()->group(group);
  cmd->add_option("--low-outlier-depth", o.low_outlier_depth_m,
                  "points this far below nearly all neighbours do not hold the cloth up, m "
                  "(0 = off)")
      ->capture_default_str()->group(group);
  cmd->add_option("--low-outlier-fraction", o.low_outlier_max_fraction,
                  "a point is also a low outlier when fewer than this fraction of the points "
                  "around it reach its level (0 = by count only)")
      ->capture_default_str()->group(group);
  std::vector<std::string> fill_names;
  for (const terrain::ClothHoleFill fill :
       {terrain::ClothHoleFill::kNeighbourMean, terrain::ClothHoleFill::kNearest,
        terrain::ClothHoleFill::kReferenceScanline}) {
    fill_names.push_back(terrain::ToString(fill));
  }
  cmd->add_option("--hole-fill", args.hole_fill,
                  "height under particles without a point: mean (of known neighbours), nearest "
                  "(nearest measured particle, the paper's nearest point; suits a cloth finer "
                  "than the point spacing), reference (along rows/columns as the original CSF "
                  "code)")
      ->check(CLI::IsMember(fill_names))
      ->capture_default_str()->group(group);
  cmd->add_option("--gravity", o.gravity,
                  "cloth gravity per step^2 (the original code's build used 0.2 dT^2)")
      ->capture_default_str()->group(group);
}

void AddSmrfOptions(CLI::App* cmd, terrain::SmrfOptions& o) {
  const char* group = "Simple morphological filter (--method smrf)";
  cmd->add_option("--smrf-cell", o.cell_m, "minimum-surface cell size (c), m")
      ->capture_default_str()->group(group);
  cmd->add_option("--smrf-slope", o.slope,
                  "slope tolerance of the progressive opening (s), rise over run")
      ->capture_default_str()->group(group);
  cmd->add_option("--smrf-window", o.max_window_m,
                  "radius of the largest opening (w), m: objects up to about twice this wide "
                  "are removed")
      ->capture_default_str()->group(group);
  cmd->add_option("--smrf-threshold", o.elevation_threshold_m,
                  "ground if within this of the provisional DEM on flat terrain (et), m")
      ->capture_default_str()->group(group);
  cmd->add_option("--smrf-scaler", o.elevation_scaler,
                  "the threshold grows by this times the DEM's slope under the point (es)")
      ->capture_default_str()->group(group);
  cmd->add_option("--smrf-low-outlier-window", o.low_outlier_window_m,
                  "window radius of the low-outlier test, m (0 = no test)")
      ->capture_default_str()->group(group);
  cmd->add_option("--smrf-low-outlier-slope", o.low_outlier_slope,
                  "slope tolerance of the low-outlier test (the paper's 500 % = 5)")
      ->capture_default_str()->group(group);
}

}  // namespace

void AddGroundCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "ground",
      "Split a cloud into ground and objects: simple morphological filter (SMRF) or cloth "
      "simulation filter (CSF)");
  static GroundArgs args;
  cmd->add_option("--in", args.in_path, "cloud (PCD/PLY/LAS), may be in UTM coordinates")
      ->required();
  cmd->add_option("--out-ground", args.ground_path,
                  "ground points to write (.las: ASPRS class 2)")->required();
  cmd->add_option("--out-objects", args.objects_path,
                  "object points to write (.las: their input class; ground and never-classified "
                  "become 1)")->required();
  cmd->add_option("--method", args.method,
                  "ground back-end: smrf (Pingel et al. 2013; the default, chosen by "
                  "leave-one-out on the ISPRS samples) or csf (Zhang et al. 2016)")
      ->check(CLI::IsMember({terrain::ToString(terrain::GroundMethod::kSmrf),
                             terrain::ToString(terrain::GroundMethod::kCsf)}))
      ->capture_default_str();
  AddSmrfOptions(cmd, args.options.smrf);
  AddCsfOptions(cmd, args);
  cmd->add_option("--json", args.json_path, "write a JSON summary here");
  cmd->callback([] { RunGround(args); });
}

}  // namespace hylo::cli
