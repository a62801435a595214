#include "hylo/inspection/visibility.h"

#include <algorithm>
#include <cmath>

#include "hylo/common/option_checks.h"
#include "hylo/inspection/ray_caster.h"

namespace hylo::inspection {
namespace {

double Radians(double deg) { return deg * M_PI / 180.0; }

// Smallest t in [0, 1] where camera + t (sample - camera) enters the box.
double BoxEntry(const TargetShape& s, const Eigen::Vector3d& camera, const Eigen::Vector3d& d) {
  double t_enter = 0.0;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) continue;  // the sample is inside the box, so the camera is in this slab
    const double near = d[i] > 0.0 ? s.region_min[i] : s.region_max[i];
    t_enter = std::max(t_enter, (near - camera[i]) / d[i]);
  }
  return std::min(t_enter, 1.0);
}

// Smallest t where camera + t d enters the sphere around the centre; the line aims at the
// centre (point targets have one sample), so it always does.
double SphereEntry(const TargetShape& s, const Eigen::Vector3d& camera, const Eigen::Vector3d& d) {
  const Eigen::Vector3d f = camera - s.centre;
  const double a = d.squaredNorm();
  const double b = 2.0 * f.dot(d);
  const double c = f.squaredNorm() - s.region_radius_m * s.region_radius_m;
  const double discriminant = std::max(0.0, b * b - 4.0 * a * c);
  return std::clamp((-b - std::sqrt(discriminant)) / (2.0 * a), 0.0, 1.0);
}

}  // namespace

bool VisibilityOptions::IsValid(std::string* why) const {
  return CheckNonNegative("camera_height_m", camera_height_m, why) &&
         CheckPositive("min_range_m", min_range_m, why) &&
         CheckPositive("max_range_m", max_range_m, why) &&
         (min_range_m < max_range_m ||
          FailOption("min_range_m", min_range_m, "must be < max_range_m", why)) &&
         CheckNonNegative("target_radius_m", target_radius_m, why) &&
         (min_visible_fraction > 0.0 ||
          FailOption("min_visible_fraction", min_visible_fraction, "must be in (0, 1]", why)) &&
         CheckInRange("min_visible_fraction", min_visible_fraction, 0.0, 1.0, why) &&
         CheckSection(occupancy, "occupancy", why);
}

TargetShape ShapeOf(const Target& target, const VisibilityOptions& options) {
  TargetShape s;
  s.centre = target.position;
  s.min_range_m = std::isnan(target.min_range_m) ? options.min_range_m : target.min_range_m;
  s.max_range_m = std::isnan(target.max_range_m) ? options.max_range_m : target.max_range_m;
  const double reach = options.occupancy.BlockedReach();
  s.samples[0] = s.centre;
  if (target.IsBox()) {
    const Eigen::Vector3d half = 0.5 * target.box_size_m;
    // The corners of the box's central half: a line to a bottom corner would graze the
    // ground the box stands on.
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d sign((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0);
      s.samples[k + 1] = s.centre + 0.5 * half.cwiseProduct(sign);
    }
    s.num_samples = 9;
    s.min_clear_lines = std::max(1, static_cast<int>(std::ceil(options.min_visible_fraction * 9 - 1e-9)));
    s.region_is_box = true;
    s.region_min = s.centre - half - Eigen::Vector3d::Constant(reach);
    s.region_max = s.centre + half + Eigen::Vector3d::Constant(reach);
  } else {
    s.region_radius_m = options.target_radius_m + reach;
  }
  if (target.HasViewDirection()) {
    s.has_direction = true;
    s.direction = {std::cos(Radians(target.view_azimuth_deg)),
                   std::sin(Radians(target.view_azimuth_deg))};
    s.cos_tolerance = std::cos(Radians(target.view_tolerance_deg));
  }
  return s;
}

bool InViewCone(const TargetShape& shape, const Eigen::Vector3d& camera) {
  const Eigen::Vector3d d = camera - shape.centre;
  const double range = d.norm();
  if (range < shape.min_range_m || range > shape.max_range_m) return false;
  if (!shape.has_direction) return true;
  const double horizontal = d.head<2>().norm();
  if (horizontal < 1e-9) return false;  // straight above or below: no azimuth
  return d.head<2>().dot(shape.direction) / horizontal >= shape.cos_tolerance;
}

bool SightLineEnd(const TargetShape& shape, int k, const Eigen::Vector3d& camera,
                  Eigen::Vector3d* end) {
  const Eigen::Vector3d d = shape.samples[k] - camera;
  double t = 0.0;
  if (shape.region_is_box) {
    if ((camera.array() >= shape.region_min.array()).all() &&
        (camera.array() <= shape.region_max.array()).all()) {
      return false;
    }
    t = BoxEntry(shape, camera, d);
  } else {
    if ((camera - shape.centre).norm() <= shape.region_radius_m) return false;
    t = SphereEntry(shape, camera, d);
  }
  *end = camera + t * d;
  return true;
}

bool SeesTarget(const TargetShape& shape, const OccupancyGrid& grid, const Eigen::Vector3d& camera) {
  int clear = 0, blocked = 0;
  const int may_block = shape.num_samples - shape.min_clear_lines;
  for (int k = 0; k < shape.num_samples; ++k) {
    Eigen::Vector3d end;
    if (SightLineEnd(shape, k, camera, &end) && !SegmentBlocked(grid, camera, end)) {
      if (++clear >= shape.min_clear_lines) return true;
    } else if (++blocked > may_block) {
      return false;
    }
  }
  return false;
}

TargetVisibility ComputeVisibility(const TargetShape& shape, const terrain::GridGeometry& geometry,
                                   const std::vector<float>& camera_z, const OccupancyGrid& grid) {
  TargetVisibility result;
  const double res = geometry.resolution_m;
  const Eigen::Vector2d lo = (shape.centre.head<2>() - Eigen::Vector2d::Constant(shape.max_range_m) -
                              geometry.corner_local) / res;
  const Eigen::Vector2d hi = (shape.centre.head<2>() + Eigen::Vector2d::Constant(shape.max_range_m) -
                              geometry.corner_local) / res;
  const int col0 = std::max(0, static_cast<int>(std::floor(lo.x())));
  const int row0 = std::max(0, static_cast<int>(std::floor(lo.y())));
  const int col1 = std::min(geometry.width - 1, static_cast<int>(std::floor(hi.x())));
  const int row1 = std::min(geometry.height - 1, static_cast<int>(std::floor(hi.y())));
  for (int row = row0; row <= row1; ++row) {
    for (int col = col0; col <= col1; ++col) {
      const std::size_t cell = geometry.Index(col, row);
      if (std::isnan(camera_z[cell])) continue;
      const Eigen::Vector3d camera = CameraAt(geometry, camera_z, cell);
      if (!InViewCone(shape, camera)) continue;
      const bool visible = SeesTarget(shape, grid, camera);
      result.cells.push_back({static_cast<uint32_t>(cell), visible});
      result.visible_cells += visible;
    }
  }
  return result;
}

}  // namespace hylo::inspection
