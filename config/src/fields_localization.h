#pragma once
// The field list (see run_config_fields.h): localization in a prior map, its start (ICP from a
// guess, else the global search), health checks and relocalization.

#include "config_sections.h"

namespace hylo::config {

template <class V>
void VisitFields(V& v, localization::IcpInitializerOptions& o) {
  v("plane_fitness_threshold_m2", o.plane_fitness_threshold_m2,
    "gate: the inliers' mean squared distance to the planes of their nearest map points must be "
    "below this, m² (> 0)");
  v("fitness_threshold_m2", o.fitness_threshold_m2,
    "gate: the mean squared nearest-neighbour distance must be below this, m² (0 = measured, "
    "not a gate; >= 0)");
  v("fitness_max_range_m", o.fitness_max_range_m,
    "points farther than this from the map (objects it lacks) are left out of the fitness, m "
    "(> 0)");
  v("inlier_distance_m", o.inlier_distance_m,
    "a scan point is an inlier when a map point lies within this, m (> 0)");
  v("min_inlier_ratio", o.min_inlier_ratio,
    "gate: inliers over finite scan points must reach this ((0, 1])");
  v("min_constraint", o.min_constraint,
    "gate: the weakest eigenvalue of the normalised point-to-plane information (0 = a free "
    "direction, 1 = fully constrained) must reach this ([0, 1))");
  v("fine_voxel_m", o.fine_voxel_m, "scan downsampling before the fine ICP, m (0 = none, >= 0)");
  v("fine_max_points", o.fine_max_points,
    "at most this many scan points in the fine ICP and the gates (>= 50)");
  v("plane_refine_iterations", o.plane_refine_iterations,
    "point-to-plane steps after the fine ICP (0 = none, >= 0)");
  v("search_enabled", o.search_enabled,
    "when the guess fails, try hypotheses around it; false: the guess alone");
  v("yaw_range_deg", o.yaw_range_deg,
    "hypotheses at yaw offsets within ±this of the guess, deg ([0, 180])");
  v("yaw_step_deg", o.yaw_step_deg, "yaw offset step, deg (> 0)");
  v("position_range_m", o.position_range_m,
    "hypotheses at x/y offsets within ±this of the guess (map frame), m (>= 0)");
  v("position_step_m", o.position_step_m, "x/y offset step, m (> 0)");
  v("max_refined_candidates", o.max_refined_candidates,
    "distinct coarse results refined by the fine ICP (>= 1)");
  v("reject_ambiguous", o.reject_ambiguous,
    "reject a start when two distinct poses pass the gates (both are reported)");
  v("max_hypotheses", o.max_hypotheses, "bound on yaw × position hypotheses (>= 1)");
}

template <class V>
void VisitFields(V& v, localization::GlobalLocalizerOptions& o) {
  v("min_range_m", o.min_range_m, "closer points are left out (the vehicle itself), m (>= 0)");
  v("max_range_m", o.max_range_m,
    "farther points are left out: sparse, and moved most by a tilt error, m (> min_range_m)");
  v("ground_clearance_m", o.ground_clearance_m,
    "points less than this above the vehicle's own ground are left out of the search (the ICP "
    "gates still see them), m (< 0 keeps them)");
  v("sensor_height_m", o.sensor_height_m,
    "height of the IMU above the ground under the wheels, a constant of the vehicle, m (0 = "
    "estimated from the scan; >= 0)");
  v("z_tolerance_m", o.z_tolerance_m,
    "how far the vehicle's height above the map's ground may be off, m (>= 0)");
  v("yaw_step_deg", o.yaw_step_deg,
    "yaw sampling, deg (0 = the angle that moves a point at max_range_m by one cell; >= 0)");
  v("max_scan_points", o.max_scan_points,
    "at most this many scan points enter the search, whose cost is proportional to them (>= 10)");
  v("max_hypotheses", o.max_hypotheses, "distinct poses kept by the search (>= 1)");
  v("min_score", o.min_score,
    "a hypothesis must explain at least this share of the scan's voxels ((0, 1])");
  v("distinct_translation_m", o.distinct_translation_m,
    "poses farther apart than this are distinct, m (> 0)");
  v("distinct_yaw_deg", o.distinct_yaw_deg, "... or turned more than this, deg (> 0)");
  v("refine_score_ratio", o.refine_score_ratio,
    "hypotheses scoring at least this times the best go through the coarse ICP ((0, 1])");
  v("fine_hypotheses", o.fine_hypotheses,
    "the best this many distinct poses after it are refined and gated (>= 1)");
  v("ambiguity_inlier_margin", o.ambiguity_inlier_margin,
    "a refined runner-up within this inlier ratio of the passing pose makes the view ambiguous "
    "([0, 1])");
  v("min_ground_support", o.min_ground_support,
    "an accepted pose must explain at least this share of the vehicle's own ground returns: a "
    "vehicle beside the map, not on it, fails ([0, 1])");
  v("judge_max_points", o.judge_max_points,
    "scan points in each hypothesis's refinement (at most icp.fine_max_points; >= 50)");
  v("judge_icp_iterations", o.judge_icp_iterations,
    "at most this many fine ICP iterations in that refinement (>= 1)");
}

template <class V>
void VisitFields(V& v, localization::GlobalMapOptions& o) {
  v("cell_m", o.cell_m, "xy cell of the raster, the search's position step, m (> 0)");
  v("z_bin_m", o.z_bin_m, "height bin of a cell's profile (64 bins), m (> 0)");
  v("levels", o.levels, "pyramid levels: the coarsest block is 2^(levels-1) cells ([1, 12])");
  v("max_cells_million", o.max_cells_million,
    "larger rasters are refused (memory), millions of cells (> 0)");
}

template <class V>
void VisitFields(V& v, localization::MovingSearchOptions& o) {
  v("enabled", o.enabled, "search while moving; false: such a start fails at once");
  v("retry_m", o.retry_m,
    "travel between two global attempts on the growing cloud, m (> 0; each attempt costs a "
    "global localization's CPU)");
  v("max_distance_m", o.max_distance_m,
    "give up after this travel, m (0 = search for as long as the vehicle moves; >= 0)");
  v("voxel_m", o.voxel_m, "the accumulated cloud keeps one point per voxel of this edge, m (> 0)");
  v("background", o.background,
    "global attempts (and the gathering of the scans they look at) run on worker threads while "
    "tracking goes on (the ROS node always); "
    "false: on the scan thread, the same result on every run of a log");
}

template <class V>
void VisitFields(V& v, LocalizationSection& c) {
  localization::LocalizationOptions& o = c.options;
  v("initial_guess", c.initial_guess,
    "start pose in the map: \"x y z roll pitch yaw\" (m, deg) or 16 numbers (the 4×4 "
    "T_world_imu, row-major); empty = none");
  v("init_scans", o.init_scans,
    "static scans gathered for the ICP start (without an IMU the first scan alone) (>= 1)");
  v("update_after_s", o.update_after_s,
    "hybrid mode: scans are added to the map from this long after localization starts, s (-1 = "
    "never: localization only; else >= 0)");
  v("health_inlier_distance_m", o.health_inlier_distance_m,
    "health: a registered point is an inlier when its matched plane lies within this of it at "
    "the final pose, m (> 0)");
  v("health_max_range_m", o.health_max_range_m,
    "larger residuals are left out of the health fitness, m (>= health_inlier_distance_m)");
  v("min_inlier_ratio", o.min_inlier_ratio,
    "a scan with a smaller share of inlier points is bad ([0, 1])");
  v("min_matches", o.min_matches, "a scan with fewer plane matches is bad (>= 0)");
  v("lost_after_scans", o.lost_after_scans,
    "bad scans in a row before the vehicle relocalizes (>= 1)");
  v("relocalize_retry_scans", o.relocalize_retry_scans,
    "scans between two failed relocalizations (>= 1)");
  v.Section("icp", o.icp,
            "the ICP initializer: the start and relocalization from a guess, and the gates every "
            "accepted pose passes");
  v("global_enabled", o.global_enabled,
    "search the whole prior map when there is no guess or the guess is rejected; false: the "
    "guess alone");
  v.Section("global", o.global,
            "the global localizer: branch and bound over a 2.5-D raster of the prior map, the "
            "best hypotheses refined and judged by the ICP gates");
  v.Section("global_map", o.global_map, "the raster of the prior map the global search reads");
  v.Section("search", o.search,
            "searching while moving, when the global search is ambiguous or finds nothing: "
            "odometry in a provisional frame, the global search retried on the growing cloud");
}

}  // namespace hylo::config
