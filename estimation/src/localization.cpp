#include "hylo/estimation/localization.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace hylo::estimation {

bool LocalizationOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (init_scans < 1) {
    os << "init_scans = " << init_scans << ": must be >= 1";
  } else if (!std::isfinite(update_after_s) || (update_after_s < 0.0 && update_after_s != -1.0)) {
    os << "update_after_s = " << update_after_s << ": must be -1 (never) or >= 0";
  } else if (!(health_inlier_distance_m > 0.0) || !std::isfinite(health_inlier_distance_m)) {
    os << "health_inlier_distance_m = " << health_inlier_distance_m << ": must be finite and > 0";
  } else if (!(health_max_range_m >= health_inlier_distance_m) ||
             !std::isfinite(health_max_range_m)) {
    os << "health_max_range_m = " << health_max_range_m
       << ": must be finite and >= health_inlier_distance_m";
  } else if (health_max_points < 10) {
    os << "health_max_points = " << health_max_points << ": must be >= 10";
  } else if (!(min_inlier_ratio >= 0.0 && min_inlier_ratio <= 1.0)) {
    os << "min_inlier_ratio = " << min_inlier_ratio << ": must be in [0, 1]";
  } else if (min_matches < 0) {
    os << "min_matches = " << min_matches << ": must be >= 0";
  } else if (lost_after_scans < 1) {
    os << "lost_after_scans = " << lost_after_scans << ": must be >= 1";
  } else if (relocalize_retry_scans < 1) {
    os << "relocalize_retry_scans = " << relocalize_retry_scans << ": must be >= 1";
  } else {
    std::string inner;
    if (icp.IsValid(&inner)) return true;
    os << "icp." << inner;
  }
  if (why != nullptr) *why = os.str();
  return false;
}

namespace {

// Distance from a registered point to the map surface: to the plane of its nearest map points
// when they are planar (sliding along a wall or the ground does not count as fitting), else to
// the nearest map point; +inf without a neighbour. `nearest` is scratch space.
double SurfaceDistance(const Eigen::Vector3f& point_map, const registration::PlaneMatcher& planes,
                       std::vector<registration::Neighbor>* nearest) {
  const registration::PlaneMatcherOptions& o = planes.options();
  planes.map().KNearest(point_map, o.num_neighbors, static_cast<float>(o.max_neighbor_distance_m),
                        nearest);
  if (nearest->empty()) return std::numeric_limits<double>::infinity();
  registration::Plane plane;
  if (static_cast<int>(nearest->size()) == o.num_neighbors &&
      registration::FitPlane(*nearest, o.planarity_threshold_m, &plane)) {
    return std::abs(plane.Distance(point_map.cast<double>()));
  }
  return std::sqrt(static_cast<double>(nearest->front().squared_distance));
}

}  // namespace

ScanHealth EvaluateScanHealth(const registration::PointCloud& points_map,
                              const registration::PlaneMatcher& planes, std::size_t num_matches,
                              const LocalizationOptions& options) {
  ScanHealth health;
  health.num_matches = num_matches;
  if (points_map.empty() || planes.map().Size() == 0) return health;
  // An even stride bounds the cost (one k-nearest query per checked point) while still
  // covering the whole sweep.
  const std::size_t max_points = static_cast<std::size_t>(options.health_max_points);
  const std::size_t stride =
      std::max<std::size_t>(1, (points_map.size() + max_points - 1) / max_points);
  const double max_range_sq = options.health_max_range_m * options.health_max_range_m;
  std::vector<registration::Neighbor> nearest;
  std::size_t checked = 0, in_range = 0, inliers = 0;
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < points_map.size(); i += stride) {
    ++checked;
    const double distance = SurfaceDistance(points_map[i], planes, &nearest);
    if (distance <= options.health_inlier_distance_m) ++inliers;
    if (nearest.empty()) continue;
    const double d_sq = nearest.front().squared_distance;
    if (d_sq > max_range_sq) continue;
    ++in_range;
    sum_sq += d_sq;
  }
  health.fitness_m2 = in_range > 0 ? sum_sq / static_cast<double>(in_range)
                                   : std::numeric_limits<double>::quiet_NaN();
  health.inlier_ratio = static_cast<double>(inliers) / static_cast<double>(checked);
  health.good = health.inlier_ratio >= options.min_inlier_ratio &&
                num_matches >= static_cast<std::size_t>(options.min_matches);
  return health;
}

std::string ToString(LocalizationEvent::Kind kind) {
  switch (kind) {
    case LocalizationEvent::Kind::kInitialized: return "initialized";
    case LocalizationEvent::Kind::kInitializationFailed: return "initialization_failed";
    case LocalizationEvent::Kind::kLost: return "lost";
    case LocalizationEvent::Kind::kRelocalized: return "relocalized";
    case LocalizationEvent::Kind::kRelocalizationFailed: return "relocalization_failed";
    case LocalizationEvent::Kind::kHybridStarted: return "hybrid_started";
  }
  return "unknown";
}

}  // namespace hylo::estimation
