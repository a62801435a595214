#pragma once
// The one viewpoint per target, among the cells that see it and that the robot can reach from
// the start: the lowest score, a weighted sum of three terms, each about 0..1:
//   range:      |range - preferred_range_m| / (max_range - min_range)  (too close crops and
//               foreshortens, too far loses thermal resolution)
//   view angle: the angle between the line of sight and the preferred one, / 90 deg: the
//               required viewing direction held horizontal, or without one the horizontal
//               (steep views up at a bushing see its underside)
//   traversal:  the costmap cost (0..1) of the cell the robot stands on while it looks (a
//               rough or sloping spot shakes the camera)
// Ties go to the cell that comes first in grid order, so a plan is reproducible.

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "hylo/inspection/visibility.h"

namespace hylo::inspection {

struct ViewpointOptions {
  double preferred_range_m = 5.0;  ///< range the camera is best at, m
  double range_weight = 1.0;       ///< weight of the range term, >= 0
  double angle_weight = 1.0;       ///< weight of the view-angle term, >= 0
  double traversal_weight = 0.5;   ///< weight of the standing cell's cost, >= 0

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

/// The angle between the line of sight (target to camera) and the preferred one, deg.
double ViewAngleDeg(const TargetShape& shape, const Eigen::Vector3d& camera);

struct Viewpoint {
  bool found = false;
  std::size_t cell = 0;                              ///< grid index
  Eigen::Vector3d camera = Eigen::Vector3d::Zero();  ///< local, m
  double range_m = 0.0;                              ///< camera to target centre, m
  double view_angle_deg = 0.0;                       ///< ViewAngleDeg
  double score = 0.0;                                ///< lower is better
  std::size_t reachable_visible_cells = 0;           ///< cells it was chosen from
};

/// The best visible cell with `reachable[cell]` set. `cost` is the costmap's cost layer
/// (NaN read as 1).
Viewpoint SelectViewpoint(const TargetShape& shape, const TargetVisibility& visibility,
                          const terrain::GridGeometry& geometry, const std::vector<float>& camera_z,
                          const std::vector<float>& cost, const std::vector<uint8_t>& reachable,
                          const ViewpointOptions& options);

}  // namespace hylo::inspection
