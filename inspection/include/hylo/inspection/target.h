#pragma once
// A point of interest the robot must look at, and what became of it in a plan.
//
// Positions are in the grid's local frame (the map frame minus GridGeometry::origin_world),
// like every coordinate inside hylo::inspection; readers and writers (hylo::io) convert.

#include <Eigen/Core>
#include <cmath>
#include <string>

namespace hylo::inspection {

/// One target. A NaN field means "use the options' default" (VisibilityOptions).
struct Target {
  std::string id;                                          ///< unique name (also a file name)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();      ///< centre, local frame, m
  double min_range_m = std::nan("");                       ///< camera-to-centre range, m
  double max_range_m = std::nan("");                       ///< camera-to-centre range, m
  Eigen::Vector3d box_size_m = Eigen::Vector3d::Zero();    ///< full sizes of an axis-aligned
                                                           ///< box around the centre, m; zero:
                                                           ///< a point
  double view_azimuth_deg = std::nan("");    ///< the camera must stand in this direction as
                                             ///< seen from the target (counter-clockwise from
                                             ///< +x, i.e. east = 0, north = 90), deg; NaN: any
  double view_tolerance_deg = std::nan("");  ///< largest horizontal deviation from
                                             ///< view_azimuth_deg, deg, in (0, 180]

  bool IsBox() const { return (box_size_m.array() > 0.0).any(); }
  bool HasViewDirection() const { return std::isfinite(view_azimuth_deg); }
  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

enum class TargetStatus {
  kPlanned,      ///< a reachable cell sees it: it has a viewpoint and a place in the route
  kOccluded,     ///< no traversable cell within range sees it
  kUnreachable,  ///< traversable cells see it, but none is reachable from the start
};

/// "planned", "occluded", "unreachable".
const char* TargetStatusName(TargetStatus status);

}  // namespace hylo::inspection
