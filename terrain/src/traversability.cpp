#include "hylo/terrain/traversability.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "hylo/common/local_origin.h"

namespace hylo::terrain {
namespace {

std::size_t CountNonFinite(const std::vector<Eigen::Vector3d>& points) {
  return std::count_if(points.begin(), points.end(),
                       [](const Eigen::Vector3d& p) { return !p.allFinite(); });
}

double Percentile(const std::vector<float>& sorted, double q) {
  const double position = q * (sorted.size() - 1);
  const std::size_t below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (position - below) * (sorted[above] - sorted[below]);
}

}  // namespace

bool TraversabilityOptions::IsValid(std::string* why) const {
  std::string inner;
  std::ostringstream os;
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m)) {
    os << "resolution_m = " << resolution_m << " must be finite and > 0";
  } else if (max_cells == 0) {
    os << "max_cells = 0 must be > 0";
  } else if (!elevation.IsValid(&inner)) {
    os << "elevation." << inner;
  } else if (!surface.IsValid(&inner)) {
    os << "surface." << inner;
  } else if (!cost.IsValid(&inner)) {
    os << "cost." << inner;
  }
  if (why) *why = os.str();
  return os.str().empty();
}

SlopeStats ComputeSlopeStats(const std::vector<float>& slope_deg) {
  std::vector<float> known;
  for (const float s : slope_deg) {
    if (!std::isnan(s)) known.push_back(s);
  }
  SlopeStats stats;
  stats.cells = known.size();
  if (known.empty()) return stats;
  std::sort(known.begin(), known.end());
  double sum = 0.0;
  for (const float s : known) sum += s;
  stats.mean_deg = sum / known.size();
  stats.median_deg = Percentile(known, 0.5);
  stats.p95_deg = Percentile(known, 0.95);
  stats.max_deg = known.back();
  return stats;
}

TraversabilityMap ComputeTraversability(const std::vector<Eigen::Vector3d>& ground_world,
                                        const std::vector<Eigen::Vector3d>& objects_world,
                                        const TraversabilityOptions& options,
                                        const StageCallback& on_stage) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("traversability options: " + why);
  const auto stage = [&](const char* name, int index) {
    if (on_stage) on_stage(name, index, 5);
  };
  TraversabilityMap map;
  TraversabilitySummary& summary = map.summary;
  summary.ground_points = ground_world.size();
  summary.ground_points_skipped = CountNonFinite(ground_world);
  summary.object_points = objects_world.size();
  summary.object_points_skipped = CountNonFinite(objects_world);
  if (summary.ground_points_skipped == summary.ground_points) {
    throw std::runtime_error("the ground cloud has no finite point (" +
                             std::to_string(summary.ground_points) + " points given)");
  }
  // Work near zero: UTM-sized coordinates would lose centimetres in float.
  const Eigen::Vector3d origin_world = ChooseOrigin(ground_world);
  const PointCloud ground_local = ToLocal(ground_world, origin_world);
  const PointCloud objects_local = ToLocal(objects_world, origin_world);

  stage("binning", 0);
  map.grid = GridMap(FitGeometry({&ground_local, &objects_local}, origin_world,
                                 options.resolution_m, options.max_cells));
  const CellPoints bins = BinPoints(map.grid.geometry(), ground_local);
  stage("elevation", 1);
  summary.elevation = ComputeElevation(ground_local, bins, options.elevation, &map.grid);
  stage("surface", 2);
  summary.surface = ComputeSurfaceLayers(ground_local, bins, options.surface, &map.grid);
  stage("cost", 3);
  map.classes = ComputeCost(options.cost, &map.grid);
  stage("obstacles", 4);
  summary.obstacles = MarkObstacles(objects_local, options.cost, &map.grid, &map.classes);
  for (const CellClass c : map.classes) ++summary.cells_per_class[static_cast<int>(c)];
  summary.slope = ComputeSlopeStats(map.grid.Layer(layers::kSlope));
  return map;
}

}  // namespace hylo::terrain
