#pragma once
// Ground / object split by the simple morphological filter (SMRF: Pingel, Clarke & McBride,
// "An improved simple morphological filter for the terrain classification of airborne LIDAR
// data", ISPRS J. Photogramm. Remote Sens. 77 (2013) 21-30):
//   1. the minimum surface: the lowest point of each cell, empty cells inpainted;
//   2. low outliers: cells far below their neighbours (the inverted surface run through the
//      filter of step 3 with a steep slope and a one-cell window);
//   3. the progressive opening: windows growing linearly, one cell per step; a cell that drops
//      by more than slope x window radius between two steps is an object;
//   4. the provisional DEM: the minimum surface without object and low-outlier cells,
//      inpainted. Here the gaps are filled with the tangent planes of the ground around them
//      (the membrane, which the morphology uses, cannot rise above a gap's rim), each ground
//      cell's lowest point is moved to the cell centre along the DEM's slope, and cells the
//      opening flagged that lie within elevation_threshold_m of the DEM are re-admitted, round
//      after round (a ridge or an embankment narrower than the window is flagged like a roof;
//      unlike a roof it connects to the ground by slopes);
//   5. every point is ground when its height above the DEM is within elevation_threshold_m
//      plus elevation_scaler times the DEM's slope under it (points on steep slopes sit
//      farther from an interpolated surface).
//
// The pieces live in separate headers, one idea each: ground_smrf_raster.h (the grid, the
// minimum surface, interpolation, slope), ground_smrf_inpaint.h (filling unknown cells),
// ground_smrf_morphology.h (opening and the progressive filter), ground_smrf_dem.h (step 4).
// This header is the entry point; ground_filter.h puts it behind the interface shared with
// the cloth filter.

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/terrain/ground_label.h"
#include "hylo/terrain/ground_smrf_raster.h"

namespace hylo::terrain {

/// Defaults: the paper's single parameter set for all 15 ISPRS samples (c 1 m, s 0.15,
/// w 18 m, et 0.5 m, es 1.25). `hylo ground` uses GroundFilterOptions, which carries the
/// setting chosen by leave-one-out on the held samples (LeaveOneOutSmrfOptions).
struct SmrfOptions {
  double cell_m = 1.0;                 ///< paper c: minimum-surface cell size, m (> 0)
  double slope = 0.15;                 ///< paper s: slope tolerance of the opening, rise over
                                       ///< run (> 0); a cell dropping more than s x radius
                                       ///< between two openings is an object
  double max_window_m = 18.0;          ///< paper w: radius of the largest opening, m (>= cell_m);
                                       ///< the widest object removed is about twice this
  double elevation_threshold_m = 0.5;  ///< paper et: ground when within this of the DEM on flat
                                       ///< terrain, m (>= 0); also the tolerance within which a
                                       ///< flagged cell is re-admitted to the DEM
  double elevation_scaler = 1.25;      ///< paper es: the threshold grows by this times the DEM's
                                       ///< slope (rise over run) under the point, m (>= 0)
  double low_outlier_slope = 5.0;      ///< paper: 500 %; low-outlier test's slope tolerance (> 0)
  double low_outlier_window_m = 1.0;   ///< paper: 1 m; radius of the low-outlier test's window,
                                       ///< m (>= 0; 0 = no low-outlier test)
  double max_cells = 5e7;              ///< refuse grids larger than this (a stray point far from
                                       ///< the rest, or a cell far too small), cells (>= 1)

  /// False (with the field, its value and the constraint in *why) when a field is out of range.
  bool IsValid(std::string* why) const;
};

/// The provisional DEM of steps 1-4, kept so that classification thresholds can be varied
/// without redoing the morphology.
struct SmrfSurface {
  smrf::Raster dem;                       ///< provisional DEM (paper ZIpro), every cell known, m
  smrf::Raster slope;                     ///< its slope (rise over run) per cell
  std::size_t num_cells_with_points = 0;  ///< cells the minimum surface got from points
  std::size_t num_low_outlier_cells = 0;  ///< flagged by step 2
  std::size_t num_object_cells = 0;       ///< flagged by step 3 (not counting low outliers)
  std::size_t num_readmitted_cells = 0;   ///< of those, re-admitted to the DEM in step 4
  int dem_rounds = 0;                     ///< DEMs step 4 built
  int max_window_cells = 0;               ///< radius of the largest opening, cells
};

/// What the filter did. `labels` has one entry per input point, in input order.
struct SmrfResult {
  bool ok = false;                            ///< false: nothing classified, see message
  std::string message;                        ///< why not ok, or a one-line description
  std::vector<GroundLabel> labels;            ///< per input point
  std::vector<float> height_above_surface_m;  ///< per input point: z - DEM under it, m (NaN
                                              ///< for invalid points)
  std::size_t num_ground = 0;
  std::size_t num_objects = 0;
  std::size_t num_invalid = 0;            ///< non-finite points (labelled kInvalid)
  int grid_cols = 0;                      ///< cells along x
  int grid_rows = 0;                      ///< cells along y
  std::size_t num_empty_cells = 0;        ///< cells without a point (inpainted)
  std::size_t num_low_outlier_cells = 0;  ///< see SmrfSurface
  std::size_t num_object_cells = 0;       ///< see SmrfSurface
  std::size_t num_readmitted_cells = 0;   ///< see SmrfSurface
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();  ///< shift used to compute near zero
};

/// Called after each opening of the progressive filter (step starts at 1).
using SmrfProgress = std::function<void(int step, int total_steps)>;

/// Classifies points given in world (possibly UTM) coordinates: an origin is chosen and kept
/// in the result, the work is done on coordinates near zero. Empty or all-NaN input, or a
/// grid above max_cells, gives ok = false. Throws std::invalid_argument when options are
/// invalid.
SmrfResult FilterGroundSmrf(const std::vector<Eigen::Vector3d>& points_world,
                            const SmrfOptions& options, const SmrfProgress& progress = {});

/// The same on a cloud already near zero (origin_world stays zero).
SmrfResult FilterGroundSmrfLocal(const PointCloud& points_local, const SmrfOptions& options,
                                 const SmrfProgress& progress = {});

/// Steps 1-4 on a cloud near zero with at least one finite point (checked) whose grid is
/// within options.max_cells (checked by the caller: FilterGroundSmrfLocal reports it).
SmrfSurface ComputeSmrfSurface(const PointCloud& points_local, const SmrfOptions& options,
                               const SmrfProgress& progress = {});

/// Step 5: labels every point of `points_local` against `surface` (fills labels, heights and
/// the point counts of *result).
void ClassifySmrf(const PointCloud& points_local, const SmrfSurface& surface,
                  double elevation_threshold_m, double elevation_scaler, SmrfResult* result);

}  // namespace hylo::terrain
