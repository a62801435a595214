#pragma once
// Which costmap cells see a target: for every cell the robot can stand on within range (and
// in the required viewing direction), sight lines from the camera on that cell to the
// target's sample points, cast through the occupancy grid.
//
// A sight line ends where it enters the target's own region: the equipment a target sits on
// is in the map too, and would otherwise block every line to it. The region is a sphere of
// target_radius_m around a point target, or the target's box, each grown by the occupancy's
// BlockedReach() (the inflated voxels of the target's own surface reach that far). A box
// target is aimed at by nine lines (its centre, then the corners of its central half: a line
// to a bottom corner would graze the ground the box stands on) and seen when at least
// min_visible_fraction of them are clear.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/inspection/occupancy_grid.h"
#include "hylo/inspection/target.h"
#include "hylo/terrain/grid_map.h"

namespace hylo::inspection {

struct VisibilityOptions {
  double camera_height_m = 1.2;       ///< camera above the ground of the robot's cell, m
  double min_range_m = 1.0;           ///< default camera-to-target range, m (a target may set
                                      ///< its own)
  double max_range_m = 15.0;          ///< default camera-to-target range, m
  double target_radius_m = 0.3;       ///< a point target's own surroundings (the part it is
                                      ///< on), which sight lines may end in, m
  double min_visible_fraction = 1.0;  ///< a box target is seen when this share of its nine
                                      ///< sight lines is clear, (0, 1]
  OccupancyOptions occupancy;         ///< the map's voxels and the clearance

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

/// A target as sight lines see it (the options' defaults filled in).
struct TargetShape {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();       ///< local frame, m
  std::array<Eigen::Vector3d, 9> samples;                 ///< what lines aim at, centre first
  int num_samples = 1;                                    ///< 1 for a point, 9 for a box
  int min_clear_lines = 1;                                ///< lines that must be clear
  bool region_is_box = false;                             ///< own region: box or sphere
  Eigen::Vector3d region_min = Eigen::Vector3d::Zero();   ///< box region, local, m
  Eigen::Vector3d region_max = Eigen::Vector3d::Zero();   ///< box region, local, m
  double region_radius_m = 0.0;                           ///< sphere region, m
  double min_range_m = 0.0, max_range_m = 0.0;            ///< camera-to-centre range, m
  bool has_direction = false;                             ///< a viewing direction is required
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();   ///< unit, target towards camera
  double cos_tolerance = -1.0;                            ///< of the largest deviation
};

TargetShape ShapeOf(const Target& target, const VisibilityOptions& options);

/// True when a camera at `camera` (local) is within range and in the viewing direction.
bool InViewCone(const TargetShape& shape, const Eigen::Vector3d& camera);

/// Where the sight line from `camera` to sample `k` enters the target's own region, into
/// *end. False when the camera is inside that region (no line to test).
bool SightLineEnd(const TargetShape& shape, int k, const Eigen::Vector3d& camera,
                  Eigen::Vector3d* end);

/// True when at least shape.min_clear_lines sight lines from `camera` are clear of blocked
/// voxels (stops as soon as the answer is known).
bool SeesTarget(const TargetShape& shape, const OccupancyGrid& grid, const Eigen::Vector3d& camera);

/// A candidate cell: in range and in the viewing direction of a target.
struct CellView {
  uint32_t cell = 0;    ///< grid index
  bool visible = false; ///< SeesTarget from the camera on this cell
};

struct TargetVisibility {
  std::vector<CellView> cells;    ///< every candidate cell, in grid order
  std::size_t visible_cells = 0;  ///< candidates that see the target
};

/// Camera positions: `camera_z[cell]` is the camera's local height on that cell, NaN where
/// the robot cannot stand. Tests every candidate cell of `shape`.
TargetVisibility ComputeVisibility(const TargetShape& shape, const terrain::GridGeometry& geometry,
                                   const std::vector<float>& camera_z, const OccupancyGrid& grid);

/// The camera on a cell: its centre at camera_z (local).
inline Eigen::Vector3d CameraAt(const terrain::GridGeometry& geometry,
                                const std::vector<float>& camera_z, std::size_t cell) {
  const Eigen::Vector2d xy = geometry.CentreLocal(geometry.Col(cell), geometry.Row(cell));
  return {xy.x(), xy.y(), static_cast<double>(camera_z[cell])};
}

}  // namespace hylo::inspection
