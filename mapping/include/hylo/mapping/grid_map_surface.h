#pragma once
// Surface layers of a grid map from the ground points around each cell: the normal from a
// principal component analysis of the neighbouring cells' points (the eigenvector of the
// smallest covariance eigenvalue), the slope (the normal's angle to vertical), the roughness
// (RMS distance of those points to their plane) and the step height (largest elevation
// difference to the neighbouring cells).

#include <cstddef>
#include <string>

#include "hylo/mapping/grid_map.h"
#include "hylo/registration/point_types.h"

namespace hylo::mapping {

struct SurfaceOptions {
  double normal_radius_m = 0.3;   ///< cells whose centres lie within this distance of a cell's
                                  ///< centre give their points to its plane fit, m
  int min_points = 6;             ///< points a plane fit needs; fewer -> no normal (NaN)
  double min_spread_cells = 0.1;  ///< smallest horizontal standard deviation of the fitted
                                  ///< points, in cells: below it the points are (nearly) one
                                  ///< line and the plane's tilt across it is not observed
  double step_radius_m = 0.3;     ///< cells within this distance are compared for the step
                                  ///< height, m (at least the 4 direct neighbours are used)

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

struct SurfaceSummary {
  std::size_t cells_with_normal = 0;     ///< elevation cells with a plane fit
  std::size_t cells_too_few_points = 0;  ///< elevation cells with < min_points around them
  std::size_t cells_degenerate = 0;      ///< points around the cell (nearly) on one line
};

/// Writes layers::kNormalX/Y/Z, kSlope (deg), kRoughness (m) and kStep (m) for every cell
/// with an elevation (measured or filled). Needs layers::kElevation (ComputeElevation).
/// `bins` must come from BinPoints on `ground_local` with the grid's geometry.
SurfaceSummary ComputeSurfaceLayers(const registration::PointCloud& ground_local,
                                    const CellPoints& bins, const SurfaceOptions& options,
                                    GridMap* grid);

}  // namespace hylo::mapping
