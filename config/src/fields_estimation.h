#pragma once
// The field list (see run_config_fields.h): the estimator's measurement, motion aids and
// back-ends, plane matching and the maps it registers against.

#include "config_sections.h"

namespace hylo::config {

template <class V>
void VisitFields(V& v, estimation::LidarUpdateOptions& o) {
  v("lidar_noise_m", o.lidar_noise_m,
    "σ of one point-to-plane residual, m (> 0); above the sensor's range noise because the "
    "errors of neighbouring matches are correlated");
  v("min_matches", o.min_matches,
    "with fewer matched points a scan brings no correction and is reported (>= 6)");
  v("min_translation_information", o.min_translation_information,
    "a scan is degenerate when the translation information per match in its weakest direction "
    "(smallest eigenvalue of Σ n nᵀ / N, 0..1) is below this (>= 0)");
  v("min_rotation_information", o.min_rotation_information,
    "... or the rotation information per match (smallest eigenvalue of Σ (q×n)(q×n)ᵀ / N) is "
    "below this, m² (>= 0)");
}

template <class V>
void VisitFields(V& v, estimation::NoImuOptions& o) {
  v("cv_translation_noise", o.cv_translation_noise,
    "constant-velocity model: random walk on the velocity, m/s/√s (> 0)");
  v("cv_rotation_noise", o.cv_rotation_noise,
    "constant-velocity model: random walk on the body rate, rad/s/√s (> 0)");
  v("yaw_search_deg", o.yaw_search_deg,
    "before iterating, try yaw offsets within ±this of the prediction and start from the one "
    "with most plane matches, deg ([0, 180]; 0 = off)");
  v("yaw_search_step_deg", o.yaw_search_step_deg, "step of that search, deg (> 0)");
}

template <class V>
void VisitFields(V& v, estimation::RobustRegistrationOptions& o) {
  v("enabled", o.enabled, "align robustly before each lidar update");
  v("coarse_voxel_m", o.coarse_voxel_m,
    "one point per voxel of this edge forms the subset aligned, m (> 0)");
  v("max_iterations", o.max_iterations, "ICP iterations of one alignment, all scales (>= 1)");
  v("initial_deviation_m", o.initial_deviation_m,
    "deviation of the motion model assumed until one is observed (KISS-ICP's initial "
    "threshold), m (> 0)");
  v("min_deviation_m", o.min_deviation_m,
    "smaller deviations are not learnt from: a vehicle at rest says nothing about the model's "
    "error, m (>= 0)");
  v("final_kernel_m", o.final_kernel_m,
    "narrowest kernel scale: the alignment stops there and the update takes the last "
    "centimetres, m (> 0)");
  v("settle_fraction", o.settle_fraction,
    "a kernel scale has settled (and halves) when a step moves the points by less than this "
    "fraction of it (> 0)");
  v("inlier_distance_m", o.inlier_distance_m,
    "quality check: a point within this of its map plane is an inlier, m (> 0)");
  v("min_inlier_share", o.min_inlier_share,
    "an alignment is accepted when its inlier fraction reaches this share of the median of "
    "recent scans' ([0, 1]; 0: only the first alignment retries)");
  v("inlier_history", o.inlier_history, "recent aligned scans that median covers (>= 1)");
  v("retry_yaw_range_deg", o.retry_yaw_range_deg,
    "a rejected alignment is retried at yaw offsets within ±this, deg ([0, 180])");
  v("retry_yaw_step_deg", o.retry_yaw_step_deg, "step of those retries, deg (> 0)");
}

template <class V>
void VisitFields(V& v, estimation::StandstillOptions& o) {
  v("enabled", o.enabled, "add v = 0 measurements while the vehicle is at rest");
  v("max_spread_ratio", o.max_spread_ratio,
    "at rest when the IMU samples' spread over the scan interval (largest axis' standard "
    "deviation) is below this multiple of the datasheet's white-noise spread (>= 1)");
  v("max_speed_mps", o.max_speed_mps, "... and the estimated speed below this, m/s (> 0)");
  v("velocity_noise_mps", o.velocity_noise_mps,
    "standard deviation of the v = 0 measurement, m/s (> 0)");
  v("min_samples", o.min_samples, "IMU samples the interval must hold (>= 3)");
}

template <class V>
void VisitFields(V& v, estimation::IeskfOptions& o) {
  v("max_iterations", o.max_iterations, "iterated-update steps per scan (>= 1)");
  v("convergence_rotation_rad", o.convergence_rotation_rad,
    "stop when a step rotates less than this, rad (> 0)");
  v("convergence_translation_m", o.convergence_translation_m,
    "... and translates less than this, m (> 0)");
  v("rematch_threshold", o.rematch_threshold,
    "planes are searched again only after a step that moved the pose more than this, m or rad "
    "(> 0)");
  v("online_extrinsic", o.online_extrinsic, "estimate T_imu_lidar in the filter");
}

template <class V>
void VisitFields(V& v, estimation::SlidingWindowOptions& o) {
  v("window_size", o.window_size, "states (scans) optimised together (>= 2)");
  v("max_iterations", o.max_iterations, "Ceres iterations per association round (>= 1)");
  v("max_solver_time_s", o.max_solver_time_s,
    "wall-time budget of all rounds of one scan, s (> 0)");
  v("linear_solver", o.linear_solver, "Ceres' linear solver");
  v("association_rounds", o.association_rounds,
    "solver rounds per scan; the newest scan's planes are searched again before each, where "
    "rematch_threshold says (>= 1)");
  v("rematch_threshold", o.rematch_threshold,
    "a round searches the planes again only when a pose of the window moved more than this "
    "since the last search, m or rad (0: before every round; >= 0)");
  v("robust_loss", o.robust_loss,
    "robust loss on the point-to-plane residuals; none: the matcher's range gate is the only "
    "outlier model, as in the filter");
  v("robust_loss_scale_m", o.robust_loss_scale_m, "residual where the robust loss bends, m (> 0)");
  v("marginalize", o.marginalize,
    "marginalise the oldest state into a prior; false: drop it (for comparisons only)");
  v("scan_pairs", o.scan_pairs,
    "match each new scan's points to planes of the window's earlier scans, which move with "
    "those scans' poses");
  v("pair_points", o.pair_points,
    "most points of a new scan matched to each earlier scan of the window (>= 1)");
  v("estimate_time_offset", o.estimate_time_offset,
    "estimate a correction to lidar.time_offset_s with the window (needs the IMU; reported in "
    "summary.json with its sigma)");
  v("estimate_extrinsic_rotation", o.estimate_extrinsic_rotation,
    "estimate a small correction to the rotation of T_imu_lidar with the window (needs the "
    "IMU; reported in summary.json with its sigma)");
  v("time_offset_prior_sigma_s", o.time_offset_prior_sigma_s,
    "prior standard deviation of the time-offset correction, s (> 0)");
  v("extrinsic_rotation_prior_sigma_rad", o.extrinsic_rotation_prior_sigma_rad,
    "prior standard deviation of the extrinsic rotation correction per axis, rad (> 0)");
}

template <class V>
void VisitFields(V& v, registration::PlaneMatcherOptions& o) {
  v("num_neighbors", o.num_neighbors, "nearest map points fitted by each plane (>= 3)");
  v("line_like_neighbors", o.line_like_neighbors,
    "when those neighbours lie along a line (a ring on the ground), search again with this "
    "many, reaching across the line (<= num_neighbors: no second search)");
  v("line_like_ratio", o.line_like_ratio,
    "neighbours are line-like when their spread across their main direction is below "
    "planarity_threshold_m and below this fraction of their spread along it ((0, 1])");
  v("max_neighbor_distance_m", o.max_neighbor_distance_m,
    "farther map points are not neighbours, m (> 0)");
  v("planarity_threshold_m", o.planarity_threshold_m,
    "every neighbour must lie within this of the plane, m (> 0)");
  v("range_gate_factor", o.range_gate_factor,
    "a match is kept when |residual| < this × √(the point's range in m), m^0.5 (> 0)");
}

template <class V>
void VisitFields(V& v, mapping::MapManagerOptions& o) {
  v("voxel_size_m", o.voxel_size_m, "downsampling voxel of the points added to the map, m (> 0)");
  v("window_size_m", o.window_size_m,
    "side of the cube of map kept around the vehicle, m (0 = keep everything)");
  v("window_margin_m", o.window_margin_m,
    "the window moves when the vehicle comes this close to a face, m (0 < margin < "
    "window_size_m / 2)");
}

template <class V>
void VisitFields(V& v, mapping::PriorMapOptions& o) {
  v("resolution_m", o.resolution_m,
    "uniform-sampling voxel applied when the map is loaded, m (0 = keep all, >= 0)");
  v("origin_granularity_m", o.origin_granularity_m,
    "the local origin is the map's first finite point rounded to this, m (>= 0)");
  v("tile_load_radius_m", o.tile_load_radius_m,
    "a tiled map's tiles within this of the vehicle are held, m (0 = the scan's reach: "
    "preprocess.max_range_m + planes.max_neighbor_distance_m; >= 0)");
  v("tile_unload_margin_m", o.tile_unload_margin_m,
    "held tiles are dropped beyond the load radius plus this, m (>= 0)");
  v("tile_cache_million_points", o.tile_cache_million_points,
    "tiles read on demand (the start, a lost vehicle, the final metrics) are cached up to this "
    "many points, millions (> 0)");
}

}  // namespace hylo::config
