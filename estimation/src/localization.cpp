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

ScanHealth EvaluateScanHealth(const registration::PointCloud& points_map,
                              const registration::NeighborSearch& map, std::size_t num_matches,
                              const LocalizationOptions& options) {
  ScanHealth health;
  health.num_matches = num_matches;
  if (points_map.empty() || map.Size() == 0) return health;
  // An even stride bounds the cost (one nearest-neighbour query per checked point) while
  // still covering the whole sweep.
  const std::size_t stride = std::max<std::size_t>(
      1, points_map.size() / static_cast<std::size_t>(options.health_max_points));
  const float max_range = static_cast<float>(options.health_max_range_m);
  const double inlier_sq = options.health_inlier_distance_m * options.health_inlier_distance_m;
  std::vector<registration::Neighbor> nearest;
  std::size_t checked = 0, in_range = 0, inliers = 0;
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < points_map.size(); i += stride) {
    ++checked;
    map.KNearest(points_map[i], 1, max_range, &nearest);
    if (nearest.empty()) continue;
    const double d_sq = nearest.front().squared_distance;
    ++in_range;
    sum_sq += d_sq;
    if (d_sq <= inlier_sq) ++inliers;
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
