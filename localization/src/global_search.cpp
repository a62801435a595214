#include "hylo/localization/global_search.h"

#include <stdexcept>

#include "hylo/common/check.h"

namespace hylo::localization {

GlobalSearch::GlobalSearch(const LocalizationOptions& options, const PointCloud& points_map,
                           const std::string& no_points_reason)
    : enabled_(options.global_enabled), localizer_(options.global, options.icp) {
  if (!enabled_) {
    why_unavailable_ = "global localization is disabled (localization.global_enabled)";
    return;
  }
  if (points_map.empty()) {
    why_unavailable_ = no_points_reason;
    return;
  }
  try {
    map_ = std::make_unique<GlobalMap>(GlobalMap::Build(points_map, options.global_map));
  } catch (const std::invalid_argument& e) {
    why_unavailable_ = e.what();
  }
}

GlobalLocalizationResult GlobalSearch::Localize(const PointCloud& scan_imu,
                                                const Eigen::Matrix3d& R_level_imu,
                                                const registration::NeighborSearch& map) const {
  HYLO_CHECK(available());
  return localizer_.Localize(scan_imu, R_level_imu, *map_, map);
}

}  // namespace hylo::localization
