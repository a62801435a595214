#pragma once
// Surface layers of a grid map from the ground points around each cell: the normal from a
// weighted principal component analysis of the points within a vehicle-footprint radius (the
// eigenvector of the smallest covariance eigenvalue; weights fall smoothly with distance, so
// the cell's own surface dominates), the slope (the normal's angle to vertical), the roughness
// (RMS distance of those points to their plane) and the step height (largest elevation
// difference to the neighbouring cells).

#include <cstddef>
#include <string>

#include "hylo/mapping/grid_map.h"
#include "hylo/registration/point_types.h"

namespace hylo::mapping {

struct SurfaceOptions {
  double normal_radius_m = 0.5;    ///< cells whose centres lie within this distance of a cell's
                                   ///< centre give their points to its plane fit, m: the scale
                                   ///< of the surface the vehicle rides on (about half a small
                                   ///< vehicle's wheelbase), larger than a gravel stone
  double fallback_radius_m = 1.0;  ///< when the footprint has too few points or they lie on a
                                   ///< line, the fit is retried over this radius before the
                                   ///< cell is left unknown, m (>= normal_radius_m)
  int min_points = 6;              ///< points a plane fit needs; fewer -> no normal (NaN)
  double min_spread_cells = 0.1;   ///< smallest horizontal standard deviation of the fitted
                                   ///< points, in cells: below it the points are (nearly) one
                                   ///< line and the plane's tilt across it is not observed
  double step_radius_m = 0.3;      ///< cells within this distance are compared for the step
                                   ///< height, m (at least the 4 direct neighbours are used)

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

struct SurfaceSummary {
  std::size_t cells_with_normal = 0;     ///< elevation cells with a plane fit
  std::size_t cells_fallback = 0;        ///< of those, fitted over fallback_radius_m
  std::size_t cells_too_few_points = 0;  ///< elevation cells with < min_points within the
                                         ///< fallback radius (left unknown)
  std::size_t cells_degenerate = 0;      ///< points within the fallback radius (nearly) on one
                                         ///< line (left unknown)
};

/// Writes layers::kNormalX/Y/Z, kSlope (deg), kRoughness (m) and kStep (m) for every cell
/// with an elevation (measured or filled). Needs layers::kElevation (ComputeElevation).
/// `bins` must come from BinPoints on `ground_local` with the grid's geometry.
SurfaceSummary ComputeSurfaceLayers(const registration::PointCloud& ground_local,
                                    const CellPoints& bins, const SurfaceOptions& options,
                                    GridMap* grid);

}  // namespace hylo::mapping
