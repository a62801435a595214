#pragma once
// The single list of configuration fields. Reading and writing both walk these functions, so
// a field added here is parsed, validated against unknown keys and saved with every run.
// Visitor interface: v(key, field) for a value, v.Section(key, struct) for a nested map,
// v.OptionalSection(key, struct, enabled) for a map that may be the scalar `none`.

#include "hylo/config/run_config.h"

namespace hylo::config {

template <class V>
void VisitFields(V& v, estimation::ImuNoise& noise) {
  v("gyro_noise_density", noise.gyro_noise_density);
  v("accel_noise_density", noise.accel_noise_density);
  v("gyro_bias_random_walk", noise.gyro_bias_random_walk);
  v("accel_bias_random_walk", noise.accel_bias_random_walk);
}

template <class V>
void VisitFields(V& v, LidarConfig& lidar) {
  v("topic", lidar.topic);
  v("time_convention", lidar.time_convention);
  v("min_range_m", lidar.min_range_m);
  v("max_range_m", lidar.max_range_m);
  v("scan_period_s", lidar.scan_period_s);
}

template <class V>
void VisitFields(V& v, ImuConfig& imu) {
  v("topic", imu.topic);
  v("rate_hz", imu.rate_hz);
  v("gravity_mps2", imu.gravity_mps2);
  v("accel_scale", imu.accel_scale);
  v.Section("noise", imu.noise);
}

template <class V>
void VisitFields(V& v, TransformConfig& transform) {
  v("translation_m", transform.translation_m);
  v("rotation_rpy_deg", transform.rotation_rpy_deg);
}

template <class V>
void VisitFields(V& v, RunConfig& run) {
  v("backend", run.backend);
  v.Section("lidar", run.lidar);
  v.OptionalSection("imu", run.imu, run.imu.enabled);
  v.Section("T_imu_lidar", run.T_imu_lidar);
}

}  // namespace hylo::config
