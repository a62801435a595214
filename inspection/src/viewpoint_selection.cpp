#include "hylo/inspection/viewpoint_selection.h"

#include <algorithm>
#include <cmath>

#include "hylo/common/option_checks.h"

namespace hylo::inspection {

bool ViewpointOptions::IsValid(std::string* why) const {
  return CheckPositive("preferred_range_m", preferred_range_m, why) &&
         CheckNonNegative("range_weight", range_weight, why) &&
         CheckNonNegative("angle_weight", angle_weight, why) &&
         CheckNonNegative("traversal_weight", traversal_weight, why);
}

double ViewAngleDeg(const TargetShape& shape, const Eigen::Vector3d& camera) {
  const Eigen::Vector3d sight = (camera - shape.centre).normalized();
  Eigen::Vector3d preferred(shape.direction.x(), shape.direction.y(), 0.0);
  if (!shape.has_direction) {
    const double horizontal = sight.head<2>().norm();
    if (horizontal < 1e-9) return 90.0;
    preferred.head<2>() = sight.head<2>() / horizontal;
  }
  return std::acos(std::clamp(sight.dot(preferred), -1.0, 1.0)) * 180.0 / M_PI;
}

Viewpoint SelectViewpoint(const TargetShape& shape, const TargetVisibility& visibility,
                          const terrain::GridGeometry& geometry, const std::vector<float>& camera_z,
                          const std::vector<float>& cost, const std::vector<uint8_t>& reachable,
                          const ViewpointOptions& options) {
  Viewpoint best;
  const double range_span = std::max(1e-6, shape.max_range_m - shape.min_range_m);
  for (const CellView& view : visibility.cells) {
    if (!view.visible || !reachable[view.cell]) continue;
    ++best.reachable_visible_cells;
    const Eigen::Vector3d camera = CameraAt(geometry, camera_z, view.cell);
    const double range = (camera - shape.centre).norm();
    const double angle = ViewAngleDeg(shape, camera);
    const float c = cost[view.cell];
    const double score = options.range_weight * std::abs(range - options.preferred_range_m) / range_span +
                         options.angle_weight * angle / 90.0 +
                         options.traversal_weight * (std::isnan(c) ? 1.0 : std::clamp(c, 0.f, 1.f));
    if (best.found && score >= best.score) continue;
    best.found = true;
    best.cell = view.cell;
    best.camera = camera;
    best.range_m = range;
    best.view_angle_deg = angle;
    best.score = score;
  }
  return best;
}

}  // namespace hylo::inspection
