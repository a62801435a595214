#pragma once
// The single list of configuration fields. Reading and writing both walk these functions, so
// a field added here is parsed, validated against unknown keys and saved with every run.
// Visitor interface: v(key, field) for a value, v.Section(key, struct) for a nested map,
// v.OptionalSection(key, struct, enabled) for a map that may be the scalar `none`.
// Each YAML section maps onto one library options struct (plus, for a few sections, an
// app-level struct beside it): the key names are the structs' field names.

#include <string>

#include "hylo/config/run_config.h"

namespace hylo::config {

/// `imu:`: the log's stream and the estimator's sensor model.
struct ImuSection {
  ImuStream& stream;
  estimation::ImuOptions& options;
};
/// `lidar:`: the log's stream and the lidar's clock offset (the pipeline's).
struct LidarSection {
  LidarStream& stream;
  estimation::PipelineLidarOptions& options;
};
/// `localization:`: the start pose given in the file, and the supervisor's settings.
struct LocalizationSection {
  std::string& initial_guess;
  estimation::LocalizationOptions& options;
};
/// `output:`: what the pipeline registers for dense maps, and the frame names.
struct OutputSection {
  estimation::PipelineOutputOptions& pipeline;
  OutputFrames& frames;
};

/// Keys that moved or went away: the message an old configuration gets instead of a bare
/// "unknown key" (nullptr for any other key).
const char* MovedKeyHint(const std::string& key_path);

template <class V>
void VisitFields(V& v, estimation::ImuNoise& noise) {
  v("gyro_noise_density", noise.gyro_noise_density);
  v("accel_noise_density", noise.accel_noise_density);
  v("gyro_bias_random_walk", noise.gyro_bias_random_walk);
  v("accel_bias_random_walk", noise.accel_bias_random_walk);
}

template <class V>
void VisitFields(V& v, LidarSection& lidar) {
  v("topic", lidar.stream.topic);
  v("time_convention", lidar.stream.time_convention);
  v("time_offset_s", lidar.options.time_offset_s);
}

template <class V>
void VisitFields(V& v, ImuSection& imu) {
  v("topic", imu.stream.topic);
  v("accel_scale", imu.stream.accel_scale);
  v("rate_hz", imu.options.rate_hz);
  v("gravity_mps2", imu.options.gravity_mps2);
  v("accel_range_mps2", imu.options.accel_range_mps2);
  v("gyro_range_radps", imu.options.gyro_range_radps);
  v.Section("noise", imu.options.noise);
}

template <class V>
void VisitFields(V& v, TransformConfig& transform) {
  v("translation_m", transform.translation_m);
  v("rotation_rpy_deg", transform.rotation_rpy_deg);
}

template <class V>
void VisitFields(V& v, estimation::PreprocessOptions& o) {
  v("min_range_m", o.min_range_m);
  v("max_range_m", o.max_range_m);
  v("scan_voxel_m", o.scan_voxel_m);
  v("point_stride", o.point_stride);
  v("max_point_offset_s", o.max_point_offset_s);
  v("min_points", o.min_points);
  v("deskew", o.deskew);
}

template <class V>
void VisitFields(V& v, estimation::ImuInitializerOptions& o) {
  v("duration_s", o.duration_s);
  v("max_accel_std_mps2", o.max_accel_std_mps2);
  v("max_gyro_std_radps", o.max_gyro_std_radps);
  v("max_gyro_mean_radps", o.max_gyro_mean_radps);
  v("gravity_tolerance_mps2", o.gravity_tolerance_mps2);
}

template <class V>
void VisitFields(V& v, estimation::InitialUncertainty& o) {
  v("rotation_sigma_rad", o.rotation_sigma_rad);
  v("velocity_sigma_mps", o.velocity_sigma_mps);
  v("gyro_bias_sigma_radps", o.gyro_bias_sigma_radps);
  v("accel_bias_sigma_mps2", o.accel_bias_sigma_mps2);
  v("gravity_sigma_mps2", o.gravity_sigma_mps2);
  v("extrinsic_rotation_sigma_rad", o.extrinsic_rotation_sigma_rad);
  v("extrinsic_translation_sigma_m", o.extrinsic_translation_sigma_m);
  v("localized_position_sigma_m", o.localized_position_sigma_m);
}

template <class V>
void VisitFields(V& v, estimation::LidarUpdateOptions& o) {
  v("lidar_noise_m", o.lidar_noise_m);
  v("min_matches", o.min_matches);
  v("min_translation_information", o.min_translation_information);
  v("min_rotation_information", o.min_rotation_information);
}

template <class V>
void VisitFields(V& v, estimation::NoImuOptions& o) {
  v("cv_translation_noise", o.cv_translation_noise);
  v("cv_rotation_noise", o.cv_rotation_noise);
  v("yaw_search_deg", o.yaw_search_deg);
  v("yaw_search_step_deg", o.yaw_search_step_deg);
}

template <class V>
void VisitFields(V& v, estimation::RobustRegistrationOptions& o) {
  v("enabled", o.enabled);
  v("coarse_voxel_m", o.coarse_voxel_m);
  v("max_iterations", o.max_iterations);
  v("initial_deviation_m", o.initial_deviation_m);
  v("min_deviation_m", o.min_deviation_m);
  v("final_kernel_m", o.final_kernel_m);
  v("settle_fraction", o.settle_fraction);
  v("inlier_distance_m", o.inlier_distance_m);
  v("min_inlier_share", o.min_inlier_share);
  v("inlier_history", o.inlier_history);
  v("retry_yaw_range_deg", o.retry_yaw_range_deg);
  v("retry_yaw_step_deg", o.retry_yaw_step_deg);
}

template <class V>
void VisitFields(V& v, estimation::StandstillOptions& o) {
  v("enabled", o.enabled);
  v("max_spread_ratio", o.max_spread_ratio);
  v("max_speed_mps", o.max_speed_mps);
  v("velocity_noise_mps", o.velocity_noise_mps);
  v("min_samples", o.min_samples);
}

template <class V>
void VisitFields(V& v, estimation::IeskfOptions& o) {
  v("max_iterations", o.max_iterations);
  v("convergence_rotation_rad", o.convergence_rotation_rad);
  v("convergence_translation_m", o.convergence_translation_m);
  v("rematch_threshold", o.rematch_threshold);
  v("online_extrinsic", o.online_extrinsic);
}

template <class V>
void VisitFields(V& v, estimation::SlidingWindowOptions& o) {
  v("window_size", o.window_size);
  v("max_iterations", o.max_iterations);
  v("max_solver_time_s", o.max_solver_time_s);
  v("linear_solver", o.linear_solver);
  v("association_rounds", o.association_rounds);
  v("robust_loss", o.robust_loss);
  v("robust_loss_scale_m", o.robust_loss_scale_m);
  v("marginalize", o.marginalize);
}

template <class V>
void VisitFields(V& v, registration::PlaneMatcherOptions& o) {
  v("num_neighbors", o.num_neighbors);
  v("line_like_neighbors", o.line_like_neighbors);
  v("line_like_ratio", o.line_like_ratio);
  v("max_neighbor_distance_m", o.max_neighbor_distance_m);
  v("planarity_threshold_m", o.planarity_threshold_m);
  v("range_gate_factor", o.range_gate_factor);
}

template <class V>
void VisitFields(V& v, mapping::MapManagerOptions& o) {
  v("voxel_size_m", o.voxel_size_m);
  v("window_size_m", o.window_size_m);
  v("window_margin_m", o.window_margin_m);
}

template <class V>
void VisitFields(V& v, mapping::PriorMapOptions& o) {
  v("resolution_m", o.resolution_m);
  v("origin_granularity_m", o.origin_granularity_m);
  v("tile_load_radius_m", o.tile_load_radius_m);
  v("tile_unload_margin_m", o.tile_unload_margin_m);
  v("tile_cache_million_points", o.tile_cache_million_points);
}

template <class V>
void VisitFields(V& v, registration::IcpInitializerOptions& o) {
  v("plane_fitness_threshold_m2", o.plane_fitness_threshold_m2);
  v("fitness_threshold_m2", o.fitness_threshold_m2);
  v("fitness_max_range_m", o.fitness_max_range_m);
  v("inlier_distance_m", o.inlier_distance_m);
  v("min_inlier_ratio", o.min_inlier_ratio);
  v("min_constraint", o.min_constraint);
  v("fine_voxel_m", o.fine_voxel_m);
  v("fine_max_points", o.fine_max_points);
  v("plane_refine_iterations", o.plane_refine_iterations);
  v("search_enabled", o.search_enabled);
  v("yaw_range_deg", o.yaw_range_deg);
  v("yaw_step_deg", o.yaw_step_deg);
  v("position_range_m", o.position_range_m);
  v("position_step_m", o.position_step_m);
  v("max_refined_candidates", o.max_refined_candidates);
  v("reject_ambiguous", o.reject_ambiguous);
  v("max_hypotheses", o.max_hypotheses);
}

template <class V>
void VisitFields(V& v, registration::GlobalLocalizerOptions& o) {
  v("min_range_m", o.min_range_m);
  v("max_range_m", o.max_range_m);
  v("ground_clearance_m", o.ground_clearance_m);
  v("sensor_height_m", o.sensor_height_m);
  v("z_tolerance_m", o.z_tolerance_m);
  v("yaw_step_deg", o.yaw_step_deg);
  v("max_scan_points", o.max_scan_points);
  v("max_hypotheses", o.max_hypotheses);
  v("min_score", o.min_score);
  v("distinct_translation_m", o.distinct_translation_m);
  v("distinct_yaw_deg", o.distinct_yaw_deg);
  v("refine_score_ratio", o.refine_score_ratio);
  v("fine_hypotheses", o.fine_hypotheses);
  v("ambiguity_inlier_margin", o.ambiguity_inlier_margin);
  v("min_ground_support", o.min_ground_support);
  v("judge_max_points", o.judge_max_points);
  v("judge_icp_iterations", o.judge_icp_iterations);
}

template <class V>
void VisitFields(V& v, registration::GlobalMapOptions& o) {
  v("cell_m", o.cell_m);
  v("z_bin_m", o.z_bin_m);
  v("levels", o.levels);
  v("max_cells_million", o.max_cells_million);
}

template <class V>
void VisitFields(V& v, estimation::MovingSearchOptions& o) {
  v("enabled", o.enabled);
  v("retry_m", o.retry_m);
  v("max_distance_m", o.max_distance_m);
  v("voxel_m", o.voxel_m);
}

template <class V>
void VisitFields(V& v, LocalizationSection& c) {
  estimation::LocalizationOptions& o = c.options;
  v("initial_guess", c.initial_guess);
  v("init_scans", o.init_scans);
  v("update_after_s", o.update_after_s);
  v("health_inlier_distance_m", o.health_inlier_distance_m);
  v("health_max_range_m", o.health_max_range_m);
  v("min_inlier_ratio", o.min_inlier_ratio);
  v("min_matches", o.min_matches);
  v("lost_after_scans", o.lost_after_scans);
  v("relocalize_retry_scans", o.relocalize_retry_scans);
  v.Section("icp", o.icp);
  v("global_enabled", o.global_enabled);
  v.Section("global", o.global);
  v.Section("global_map", o.global_map);
  v.Section("search", o.search);
}

template <class V>
void VisitFields(V& v, OutputSection& output) {
  v("dense_map_voxel_m", output.pipeline.dense_map_voxel_m);
  v("map_frame", output.frames.map_frame);
  v("odom_frame", output.frames.odom_frame);
  v("base_frame", output.frames.base_frame);
}

template <class V>
void VisitFields(V& v, terrain::ClothFilterOptions& o) {
  v("cloth_resolution_m", o.cloth_resolution_m);
  v("rigidness", o.rigidness);
  v("time_step", o.time_step);
  v("max_iterations", o.max_iterations);
  v("class_threshold_m", o.class_threshold_m);
  v("class_distance_along_normal", o.class_distance_along_normal);
  v("slope_smoothing", o.slope_smoothing);
  v("slope_height_threshold_m", o.slope_height_threshold_m);
  v("slope_max_cloth_gap_m", o.slope_max_cloth_gap_m);
  v("slope_min_region_particles", o.slope_min_region_particles);
  v("convergence_threshold_m", o.convergence_threshold_m);
  v("hole_fill", o.hole_fill);
  v("low_outlier_depth_m", o.low_outlier_depth_m);
  v("low_outlier_cell_m", o.low_outlier_cell_m);
  v("low_outlier_min_support", o.low_outlier_min_support);
  v("low_outlier_max_fraction", o.low_outlier_max_fraction);
  v("gravity", o.gravity);
  v("damping", o.damping);
}

template <class V>
void VisitFields(V& v, terrain::SmrfOptions& o) {
  v("cell_m", o.cell_m);
  v("slope", o.slope);
  v("max_window_m", o.max_window_m);
  v("elevation_threshold_m", o.elevation_threshold_m);
  v("elevation_scaler", o.elevation_scaler);
  v("low_outlier_slope", o.low_outlier_slope);
  v("low_outlier_window_m", o.low_outlier_window_m);
  v("max_cells", o.max_cells);
}

template <class V>
void VisitFields(V& v, terrain::GroundFilterOptions& o) {
  v("method", o.method);
  v.Section("csf", o.csf);
  v.Section("smrf", o.smrf);
}

template <class V>
void VisitFields(V& v, inspection::OccupancyOptions& o) {
  v("voxel_size_m", o.voxel_size_m);
  v("clearance_m", o.clearance_m);
  v("max_voxels_million", o.max_voxels_million);
}

template <class V>
void VisitFields(V& v, inspection::VisibilityOptions& o) {
  v("camera_height_m", o.camera_height_m);
  v("min_range_m", o.min_range_m);
  v("max_range_m", o.max_range_m);
  v("target_radius_m", o.target_radius_m);
  v("min_visible_fraction", o.min_visible_fraction);
  v.Section("occupancy", o.occupancy);
}

template <class V>
void VisitFields(V& v, inspection::SearchOptions& o) {
  v("robot_radius_m", o.robot_radius_m);
  v("cost_weight", o.cost_weight);
}

template <class V>
void VisitFields(V& v, inspection::ViewpointOptions& o) {
  v("preferred_range_m", o.preferred_range_m);
  v("range_weight", o.range_weight);
  v("angle_weight", o.angle_weight);
  v("traversal_weight", o.traversal_weight);
}

template <class V>
void VisitFields(V& v, inspection::TourOptions& o) {
  v("return_to_start", o.return_to_start);
  v("exact_max_stops", o.exact_max_stops);
}

template <class V>
void VisitFields(V& v, inspection::InspectionOptions& o) {
  v.Section("visibility", o.visibility);
  v.Section("search", o.search);
  v.Section("viewpoint", o.viewpoint);
  v.Section("tour", o.tour);
  v("start_snap_radius_m", o.start_snap_radius_m);
}

template <class V>
void VisitFields(V& v, RunConfig& run) {
  estimation::OdometryPipelineOptions& p = run.pipeline;
  LidarSection lidar{run.lidar, p.lidar};
  ImuSection imu{run.imu, p.imu};
  LocalizationSection localization{run.initial_guess, p.localization};
  OutputSection output{p.output, run.output};
  v("backend", p.estimator.backend);
  v.Section("lidar", lidar);
  v.OptionalSection("imu", imu, p.imu.enabled);
  v.Section("T_imu_lidar", run.T_imu_lidar);
  v.Section("preprocess", p.preprocess);
  v.Section("init", p.init);
  v.Section("initial_uncertainty", p.initial_uncertainty);
  v.Section("lidar_update", p.estimator.lidar_update);
  v.Section("no_imu", p.estimator.no_imu);
  v.Section("robust_registration", p.estimator.robust_registration);
  v.Section("standstill", p.estimator.standstill);
  v.Section("ieskf", p.estimator.ieskf);
  v.Section("sliding_window", p.estimator.sliding_window);
  v.Section("planes", p.planes);
  v.Section("map", p.map);
  v.Section("prior_map", run.prior_map);
  v.Section("localization", localization);
  v.Section("output", output);
  v.Section("ground", run.ground);
  v.Section("inspection", run.inspection);
}

}  // namespace hylo::config
