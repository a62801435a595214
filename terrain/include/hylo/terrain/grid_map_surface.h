#pragma once
// Surface layers of a grid map from the ground points around each cell: the normal from a
// weighted principal component analysis of the points within a vehicle-footprint radius (the
// eigenvector of the smallest covariance eigenvalue; weights fall smoothly with distance, so
// the cell's own surface dominates), the slope (the normal's angle to vertical), the roughness
// (RMS distance of those points to their plane) and the step height (largest elevation
// difference to the neighbouring cells).
//
// Near a break (a trench wall, a bank's edge) the centred footprint mixes two surfaces and
// gives a slope that belongs to neither. The scale is therefore adaptive: of the square blocks
// of 1, 2 x 2 and 3 x 3 cells that contain the cell, the most planar one is fitted too, and
// its normal replaces the footprint's when the two disagree by more than their noise allows
// (intersection of confidence intervals, Katkovnik 1999). A cell next to a cell without
// elevation is left unknown (unknown_at_data_edge): the unseen side may hide a drop.

#include <cstddef>
#include <string>

#include "hylo/common/point_types.h"
#include "hylo/terrain/grid_map.h"

namespace hylo::terrain {

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
  double scale_consistency_sigmas =
      2.0;                           ///< adaptive scale: the most planar block of 1 to
                                     ///< 3 x 3 cells containing the cell replaces the footprint
                                     ///< plane when their normals differ by more than this many
                                     ///< tilt standard deviations (their sum; per-cell noise =
                                     ///< SurfaceSummary::noise_m); 0 = always the footprint
  bool unknown_at_data_edge = true;  ///< no normal, slope or roughness (unknown) for a cell
                                     ///< one of whose four neighbours has no elevation (no
                                     ///< ground point, and not a small hole filled by
                                     ///< ElevationOptions::max_hole_size_m): the unseen side may
                                     ///< hide a drop, such as the occluded wall of a trench
                                     ///< whose lip alone was hit
  double step_radius_m = 0.3;        ///< cells within this distance are compared for the step
                                     ///< height, m (at least the 4 direct neighbours are used)

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

struct SurfaceSummary {
  double noise_m = 0.0;                  ///< height noise behind the tilt standard deviations:
                                         ///< median RMS distance of the footprint fits, m
  std::size_t cells_at_data_edge = 0;    ///< elevation cells left unknown by
                                         ///< unknown_at_data_edge (not fitted)
  std::size_t cells_finer_scale = 0;     ///< cells whose normal comes from a neighbourhood
                                         ///< finer than the footprint (adaptive scale)
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
SurfaceSummary ComputeSurfaceLayers(const PointCloud& ground_local, const CellPoints& bins,
                                    const SurfaceOptions& options, GridMap* grid);

}  // namespace hylo::terrain
