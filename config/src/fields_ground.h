#pragma once
// The field list (see run_config_fields.h): ground extraction of a finished map.

#include "config_sections.h"

namespace hylo::config {

template <class V>
void VisitFields(V& v, terrain::ClothFilterOptions& o) {
  v("cloth_resolution_m", o.cloth_resolution_m,
    "horizontal spacing of the cloth's particles (the paper's GR), m (> 0)");
  v("rigidness", o.rigidness,
    "constraint passes per step (RI): the paper's 1 soft .. 3 hard, stiffer up to 10 ([1, 10])");
  v("time_step", o.time_step, "simulation time step (dT), simulation units (> 0)");
  v("max_iterations", o.max_iterations, "simulation steps at most (>= 1)");
  v("class_threshold_m", o.class_threshold_m,
    "a point closer than this to the cloth is ground (hcc), m (> 0)");
  v("class_distance_along_normal", o.class_distance_along_normal,
    "measure the distance to the cloth's surface; false: the vertical gap, as the reference "
    "code, which makes ground on steep slopes look like objects");
  v("slope_smoothing", o.slope_smoothing, "post-process movable particles on steep slopes (ST)");
  v("slope_height_threshold_m", o.slope_height_threshold_m,
    "post-processing pins a movable particle that continues a pinned neighbour within this "
    "height, m (> 0)");
  v("slope_max_cloth_gap_m", o.slope_max_cloth_gap_m,
    "... only where the settled cloth is closer than this to the surface (not a cloth spanning "
    "a bridge deck), m (> 0; .inf = no test, as the reference code)");
  v("slope_min_region_particles", o.slope_min_region_particles,
    "post-processing only touches movable regions of more than this many particles (>= 0)");
  v("convergence_threshold_m", o.convergence_threshold_m,
    "stop when no particle moved more than this in one step, m (0 = run every step; >= 0)");
  v("hole_fill", o.hole_fill,
    "surface height under particles without a point: the mean of known neighbours, the nearest "
    "measured particle, or along rows then columns as the reference code");
  v("low_outlier_depth_m", o.low_outlier_depth_m,
    "points this far below nearly all their neighbours do not hold the cloth up (they are still "
    "classified), m (0 = keep all; >= 0)");
  v("low_outlier_cell_m", o.low_outlier_cell_m,
    "neighbourhood of that test: 3×3 cells of this size, m (> 0)");
  v("low_outlier_min_support", o.low_outlier_min_support,
    "a point needs this many neighbours within low_outlier_depth_m of it to stay (>= 1)");
  v("low_outlier_max_fraction", o.low_outlier_max_fraction,
    "... and at least this fraction of its neighbours ([0, 1); 0 = the count alone)");
  v("gravity", o.gravity, "downward acceleration of a particle, cloth units per step² (> 0)");
  v("damping", o.damping, "fraction of a particle's velocity lost per step ([0, 1))");
}

template <class V>
void VisitFields(V& v, terrain::SmrfOptions& o) {
  v("cell_m", o.cell_m, "cell of the minimum surface (the paper's c), m (> 0)");
  v("slope", o.slope, "slope tolerance of the progressive opening (s), rise over run (> 0)");
  v("max_window_m", o.max_window_m,
    "radius of the largest opening (w): objects up to about twice this wide are removed, m "
    "(>= cell_m)");
  v("elevation_threshold_m", o.elevation_threshold_m,
    "ground when within this of the surface on flat terrain (et), m (>= 0)");
  v("elevation_scaler", o.elevation_scaler,
    "the threshold grows by this times the surface's slope under the point (es), m (>= 0)");
  v("low_outlier_slope", o.low_outlier_slope,
    "slope tolerance of the low-outlier test (the paper's 500 % = 5) (> 0)");
  v("low_outlier_window_m", o.low_outlier_window_m,
    "radius of the low-outlier test's window, m (0 = no test; >= 0)");
  v("max_cells", o.max_cells,
    "larger grids are refused: a stray far point, or too small a cell (>= 1)");
}

template <class V>
void VisitFields(V& v, terrain::GroundFilterOptions& o) {
  v("method", o.method, "the back-end that runs");
  v.Section("csf", o.csf,
            "the cloth simulation filter (Zhang et al. 2016), used when method is csf");
  v.Section("smrf", o.smrf,
            "the simple morphological filter (Pingel et al. 2013), used when method is smrf");
}

}  // namespace hylo::config
