#include "site_mapping_steps.h"

#include <chrono>
#include <stdexcept>

#include "hylo/io/cloud_io.h"
#include "hylo/io/costmap_io.h"

namespace hylo::cli {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The points of `cloud` labelled `label`, with their attributes.
io::CloudFile Select(const io::CloudFile& cloud, const std::vector<terrain::GroundLabel>& labels,
                     terrain::GroundLabel label) {
  io::CloudFile out;
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    if (labels[i] != label) continue;
    out.positions.push_back(cloud.positions[i]);
    if (!cloud.intensity.empty()) out.intensity.push_back(cloud.intensity[i]);
    if (!cloud.normals.empty()) out.normals.push_back(cloud.normals[i]);
    if (!cloud.labels.empty()) out.labels.push_back(cloud.labels[i]);
  }
  return out;
}

}  // namespace

io::Json CraftStep::ToJson() const {
  io::Json j = io::Json::object();
  j["input_points"] = input_points;
  j["output_points"] = output_points;
  j["seconds"] = seconds;
  return j;
}

CraftStep CraftFile(const std::string& in_path, const std::string& out_path,
                    const terrain::CraftOptions& options) {
  const io::CloudFile raw = io::ReadCloud(in_path);
  terrain::CraftResult result = terrain::CraftMap(raw.positions, options);
  if (!result.ok) throw std::runtime_error(in_path + ": " + result.message);
  CraftStep step;
  step.input_points = raw.positions.size();
  step.output_points = result.points_world.size();
  step.seconds = result.sampling_seconds + result.mls_seconds;
  io::CloudFile clean;
  clean.positions = std::move(result.points_world);
  clean.normals = std::move(result.normals);
  io::WriteCloud(out_path, clean, io::CloudEncoding::kBinary);
  return step;
}

io::Json GroundStep::ToJson() const {
  io::Json j = io::Json::object();
  j["method"] = method;
  j["ground_points"] = ground_points;
  j["object_points"] = object_points;
  j["seconds"] = seconds;
  return j;
}

GroundStep GroundFile(const std::string& in_path, const std::string& ground_path,
                      const std::string& objects_path,
                      const terrain::GroundFilterOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const io::CloudFile cloud = io::ReadCloud(in_path);
  const terrain::GroundFilterResult r = terrain::ExtractGround(cloud.positions, options);
  if (!r.ok) throw std::runtime_error(in_path + ": " + r.message);
  io::WriteCloud(ground_path, Select(cloud, r.labels, terrain::GroundLabel::kGround));
  io::WriteCloud(objects_path, Select(cloud, r.labels, terrain::GroundLabel::kObject));
  GroundStep step;
  step.method = terrain::ToString(r.method);
  step.ground_points = r.num_ground;
  step.object_points = r.num_objects;
  step.seconds = SecondsSince(start);
  return step;
}

io::Json TraversabilityStep::ToJson() const {
  io::Json j = io::Json::object();
  j["resolution_m"] = resolution_m;
  j["width"] = width;
  j["height"] = height;
  for (int c = 0; c < terrain::kNumCellClasses; ++c) {
    j["cells"][terrain::CellClassName(static_cast<terrain::CellClass>(c))] = cells[c];
  }
  j["slope_deg"]["median"] = slope.median_deg;
  j["slope_deg"]["p95"] = slope.p95_deg;
  j["slope_deg"]["max"] = slope.max_deg;
  j["seconds"] = seconds;
  return j;
}

TraversabilityStep TraversabilityFiles(const std::string& ground_path,
                                       const std::string& objects_path, const std::string& out_dir,
                                       const terrain::TraversabilityOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Eigen::Vector3d> ground = io::ReadCloud(ground_path).positions;
  if (ground.empty()) throw std::runtime_error(ground_path + ": the ground cloud is empty");
  const std::vector<Eigen::Vector3d> objects =
      objects_path.empty() ? std::vector<Eigen::Vector3d>{} : io::ReadCloud(objects_path).positions;
  const terrain::TraversabilityMap map = terrain::ComputeTraversability(ground, objects, options);
  TraversabilityStep step;
  step.files = io::WriteTraversabilityFiles(out_dir, map);
  step.cells = map.summary.cells_per_class;
  step.resolution_m = map.grid.geometry().resolution_m;
  step.width = map.grid.geometry().width;
  step.height = map.grid.geometry().height;
  step.slope = map.summary.slope;
  step.seconds = SecondsSince(start);
  return step;
}

}  // namespace hylo::cli
