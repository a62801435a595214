// Localization options, the health of one scan and the names of localization events.
#include <cmath>
#include <limits>

#include "hylo/common/option_checks.h"
#include "hylo/localization/localization.h"

namespace hylo::localization {

bool LocalizationOptions::IsValid(std::string* why) const {
  if (!CheckAtLeast("init_scans", init_scans, 1, "", why)) return false;
  if (!std::isfinite(update_after_s) || (update_after_s < 0.0 && update_after_s != -1.0)) {
    return FailOption("update_after_s", update_after_s, "must be -1 (never) or >= 0 s", why);
  }
  if (!CheckPositive("health_inlier_distance_m", health_inlier_distance_m, why)) return false;
  if (!(std::isfinite(health_max_range_m) && health_max_range_m >= health_inlier_distance_m)) {
    return FailOption("health_max_range_m", health_max_range_m,
                      "must be finite and >= health_inlier_distance_m", why);
  }
  return CheckInRange("min_inlier_ratio", min_inlier_ratio, 0.0, 1.0, why) &&
         CheckAtLeast("min_matches", min_matches, 0, "", why) &&
         CheckAtLeast("lost_after_scans", lost_after_scans, 1, "", why) &&
         CheckAtLeast("relocalize_retry_scans", relocalize_retry_scans, 1, "", why) &&
         CheckSection(icp, "icp", why) && CheckSection(global, "global", why) &&
         CheckSection(global_map, "global_map", why) && CheckSection(search, "search", why);
}

bool MovingSearchOptions::IsValid(std::string* why) const {
  return CheckPositive("retry_m", retry_m, why) &&
         CheckNonNegative("max_distance_m", max_distance_m, why) &&
         CheckPositive("voxel_m", voxel_m, why);
}

ScanHealth EvaluateScanHealth(const estimation::UpdateSummary& update, const LocalizationOptions& options) {
  ScanHealth health;
  health.num_matches = update.num_matches;
  if (update.point_residuals_m.empty()) return health;
  std::size_t inliers = 0, in_range = 0;
  double sum_sq = 0.0;
  for (float r : update.point_residuals_m) {
    if (!std::isfinite(r)) continue;  // no plane: not on a known surface
    const double distance = std::abs(r);
    if (distance <= options.health_inlier_distance_m) ++inliers;
    if (distance > options.health_max_range_m) continue;
    ++in_range;
    sum_sq += distance * distance;
  }
  health.fitness_m2 = in_range > 0 ? sum_sq / static_cast<double>(in_range)
                                   : std::numeric_limits<double>::quiet_NaN();
  health.inlier_ratio =
      static_cast<double>(inliers) / static_cast<double>(update.point_residuals_m.size());
  health.good = health.inlier_ratio >= options.min_inlier_ratio &&
                update.num_matches >= static_cast<std::size_t>(options.min_matches);
  return health;
}

std::string ToString(LocalizationEvent::Kind kind) {
  switch (kind) {
    case LocalizationEvent::Kind::kInitialized:
      return "initialized";
    case LocalizationEvent::Kind::kInitializationFailed:
      return "initialization_failed";
    case LocalizationEvent::Kind::kLost:
      return "lost";
    case LocalizationEvent::Kind::kRelocalized:
      return "relocalized";
    case LocalizationEvent::Kind::kRelocalizationFailed:
      return "relocalization_failed";
    case LocalizationEvent::Kind::kHybridStarted:
      return "hybrid_started";
    case LocalizationEvent::Kind::kLeftMap:
      return "left_map";
    case LocalizationEvent::Kind::kReenteredMap:
      return "reentered_map";
    case LocalizationEvent::Kind::kSearching:
      return "searching";
  }
  return "unknown";
}

}  // namespace hylo::localization
