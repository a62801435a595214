#pragma once
// Elevation layer of a grid map, with limited hole filling: only small gaps enclosed by data
// (a shadow behind a post, a missing scan line) are interpolated; large unseen areas stay
// unknown, because inventing terrain there would let a planner drive into the unseen.

#include <cstddef>
#include <string>

#include "hylo/common/point_types.h"
#include "hylo/terrain/grid_map.h"

namespace hylo::terrain {

struct ElevationOptions {
  int min_points_per_cell = 1;   ///< ground points a cell needs for a measured elevation
  double max_hole_size_m = 0.6;  ///< a hole is filled only when its bounding box is at most
                                 ///< this wide in x and in y, m; 0 disables hole filling

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

struct ElevationSummary {
  std::size_t measured_cells = 0;   ///< cells with >= min_points_per_cell points
  std::size_t filled_cells = 0;     ///< cells given an interpolated elevation
  std::size_t holes_filled = 0;     ///< enclosed gaps small enough to fill
  std::size_t holes_too_large = 0;  ///< enclosed gaps left unknown (wider than max_hole_size_m)
};

/// Writes layers::kElevation (mean z of the cell's points, local frame, NaN = no data),
/// layers::kPointCount and layers::kFilled into `grid`. `bins` must come from BinPoints on
/// `ground_local` with the grid's geometry.
ElevationSummary ComputeElevation(const PointCloud& ground_local, const CellPoints& bins,
                                  const ElevationOptions& options, GridMap* grid);

/// Fills holes of `elevation` in place: 4-connected regions of NaN cells that do not touch
/// the grid border and whose bounding box is at most `max_hole_cells` wide in both axes.
/// Each hole cell gets the inverse-distance-squared mean of the known cells bordering the
/// hole. `filled` (same size) is set to 1 where a value was written.
ElevationSummary FillHoles(const GridGeometry& geometry, int max_hole_cells,
                           std::vector<float>* elevation, std::vector<float>* filled);

}  // namespace hylo::terrain
