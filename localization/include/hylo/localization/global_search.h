#pragma once
// Whether the whole prior map can be searched for the vehicle, and that search. One object
// answers "is a global search available, and if not, why": the setting
// (localization.global_enabled), a map that could be rastered, a tiled map with an overview.
// The start, the search while moving and the relocalization of a lost vehicle all ask it.

#include <Eigen/Core>
#include <memory>
#include <string>

#include "hylo/common/point_types.h"
#include "hylo/localization/global_localizer.h"
#include "hylo/localization/global_map.h"
#include "hylo/localization/localization.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::localization {

class GlobalSearch {
 public:
  /// Rasterises `points_map` (the prior, local frame, or a tiled map's overview) when
  /// options.global_enabled. An empty cloud or one the raster refuses leaves the search
  /// unavailable, `no_points_reason` (or the raster's error) saying why.
  GlobalSearch(const LocalizationOptions& options, const PointCloud& points_map,
               const std::string& no_points_reason = "the prior map has no point");

  /// The user allowed global searches (localization.global_enabled).
  bool enabled() const { return enabled_; }
  /// Enabled and a raster to search.
  bool available() const { return map_ != nullptr; }
  /// Why available() is false, one line ("" when it is available).
  const std::string& why_unavailable() const { return why_unavailable_; }

  /// The global localizer on `scan_imu` levelled by `R_level_imu`, refined against `map`.
  /// Only when available() (hylo::InternalError otherwise).
  GlobalLocalizationResult Localize(const PointCloud& scan_imu, const Eigen::Matrix3d& R_level_imu,
                                    const registration::NeighborSearch& map) const;

 private:
  bool enabled_;
  GlobalLocalizer localizer_;
  std::unique_ptr<GlobalMap> map_;  // null: unavailable
  std::string why_unavailable_;
};

}  // namespace hylo::localization
