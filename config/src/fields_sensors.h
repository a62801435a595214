#pragma once
// The field list (see run_config_fields.h): the sensors, their mounting, the scan clean-up, the
// start, and what a run writes.

#include "config_sections.h"

namespace hylo::config {

template <class V>
void VisitFields(V& v, LidarSection& lidar) {
  v("topic", lidar.stream.topic, "sensor_msgs/PointCloud2 topic in a bag");
  v("time_convention", lidar.stream.time_convention,
    "how the driver stamps each point (field and unit); auto: detected from the fields");
  v("time_offset_s", lidar.options.time_offset_s,
    "offset of the IMU's clock from the lidar's, t_imu = t_lidar + offset (FAST-LIO's "
    "time_offset_lidar_to_imu, same sign), s (|offset| <= 1)");
}

template <class V>
void VisitFields(V& v, estimation::ImuNoise& noise) {
  v("gyro_noise_density", noise.gyro_noise_density, "gyro white noise, rad/s/√Hz (>= 0)");
  v("accel_noise_density", noise.accel_noise_density, "accelerometer white noise, m/s²/√Hz (>= 0)");
  v("gyro_bias_random_walk", noise.gyro_bias_random_walk,
    "gyro bias random walk, rad/s²/√Hz (>= 0)");
  v("accel_bias_random_walk", noise.accel_bias_random_walk,
    "accelerometer bias random walk, m/s³/√Hz (>= 0)");
}

template <class V>
void VisitFields(V& v, ImuSection& imu) {
  v("topic", imu.stream.topic, "sensor_msgs/Imu topic in a bag");
  v("accel_scale", imu.stream.accel_scale,
    "multiplies accelerations: 1 for drivers that report m/s², about gravity_mps2 for drivers "
    "that report g (Livox)");
  v("rate_hz", imu.options.rate_hz,
    "nominal sample rate, Hz (> 0); five missing samples in a row are a gap");
  v("gravity_mps2", imu.options.gravity_mps2, "local gravity magnitude, m/s² ([9.7, 9.9])");
  v("accel_range_mps2", imu.options.accel_range_mps2,
    "accelerometer full scale: a sample reading this on any axis is clipped, dropped and "
    "counted, m/s² (0 = no check, else >= 2 g)");
  v("gyro_range_radps", imu.options.gyro_range_radps,
    "gyro full scale: a sample reading this on any axis is clipped, dropped and counted, rad/s "
    "(0 = no check, >= 0)");
  v.Section("noise", imu.options.noise,
            "continuous-time noise densities and bias random walks, as datasheets and Kalibr "
            "state them");
}

template <class V>
void VisitFields(V& v, TransformConfig& transform) {
  v("translation_m", transform.translation_m, "the lidar's origin in the IMU frame, m");
  v("rotation_rpy_deg", transform.rotation_rpy_deg,
    "roll, pitch, yaw of the lidar frame in the IMU frame, deg (each within [-360, 360])");
}

template <class V>
void VisitFields(V& v, odometry::PreprocessOptions& o) {
  v("min_range_m", o.min_range_m, "closer returns are dropped (the vehicle itself), m (>= 0)");
  v("max_range_m", o.max_range_m, "farther returns are dropped, m (> min_range_m)");
  v("scan_voxel_m", o.scan_voxel_m, "uniform-sampling voxel of each scan, m (0 = keep all)");
  v("point_stride", o.point_stride,
    "before the voxel, keep every n-th return of each ring: less work on dense sensors, sparser "
    "far surfaces (>= 1)");
  v("max_point_offset_s", o.max_point_offset_s,
    "a point stamped later than this after its scan's start has a bad time and is dropped, s "
    "(> 0)");
  v("min_points", o.min_points, "a scan with fewer points after clean-up is skipped (>= 1)");
  v("deskew", o.deskew, "undistort each scan with the IMU's motion (always off without an IMU)");
}

template <class V>
void VisitFields(V& v, estimation::ImuInitializerOptions& o) {
  v("duration_s", o.duration_s, "rest period averaged, s (> 0)");
  v("max_accel_std_mps2", o.max_accel_std_mps2,
    "a larger spread of |a| means the vehicle moves, m/s² (> 0)");
  v("max_gyro_std_radps", o.max_gyro_std_radps,
    "a larger spread of the rate means the vehicle moves, rad/s (> 0)");
  v("max_gyro_mean_radps", o.max_gyro_mean_radps,
    "a larger mean rate is turning, not bias, rad/s (> 0)");
  v("gravity_tolerance_mps2", o.gravity_tolerance_mps2,
    "the mean |a| must lie within this of imu.gravity_mps2, m/s² (> 0)");
}

template <class V>
void VisitFields(V& v, estimation::InitialUncertainty& o) {
  v("rotation_sigma_rad", o.rotation_sigma_rad, "roll, pitch and yaw, rad (> 0)");
  v("velocity_sigma_mps", o.velocity_sigma_mps, "velocity, m/s (> 0)");
  v("gyro_bias_sigma_radps", o.gyro_bias_sigma_radps, "gyro bias, rad/s (> 0)");
  v("accel_bias_sigma_mps2", o.accel_bias_sigma_mps2, "accelerometer bias, m/s² (> 0)");
  v("gravity_sigma_mps2", o.gravity_sigma_mps2, "gravity vector, m/s² (> 0)");
  v("extrinsic_rotation_sigma_rad", o.extrinsic_rotation_sigma_rad,
    "rotation of T_imu_lidar, rad (> 0)");
  v("extrinsic_translation_sigma_m", o.extrinsic_translation_sigma_m,
    "translation of T_imu_lidar, m (> 0)");
  v("localized_position_sigma_m", o.localized_position_sigma_m,
    "position after an accepted ICP start or relocalization, m (> 0); in SLAM the first "
    "position defines the map frame and is held tight");
  v("moving_tilt_sigma_rad", o.moving_tilt_sigma_rad,
    "roll and pitch of a start on the move (or of a lost vehicle's search), whose gravity "
    "was read while accelerating, rad (> 0)");
  v("moving_velocity_sigma_mps", o.moving_velocity_sigma_mps,
    "velocity of a start on the move, which starts at zero, m/s (> 0)");
  v("moving_gyro_bias_sigma_radps", o.moving_gyro_bias_sigma_radps,
    "gyro bias of a start on the move, which starts at zero, rad/s (> 0)");
}

template <class V>
void VisitFields(V& v, OutputSection& output) {
  v("dense_map_voxel_m", output.pipeline.dense_map_voxel_m,
    "every scan, deskewed and registered, is kept at this voxel for map_dense.pcd, m (0 = off, "
    "else >= 0.01)");
  v("map_frame", output.frames.map_frame, "the prior map's (or the SLAM map's) frame");
  v("odom_frame", output.frames.odom_frame,
    "the continuous frame; relocalization jumps go into map → odom");
  v("base_frame", output.frames.base_frame,
    "the IMU (body) frame; publish a static transform for another base");
}

}  // namespace hylo::config
