#pragma once
// One YAML file configures a run. This is the only place where YAML becomes the plain option
// structs of the libraries: unknown keys are errors naming the key path, missing keys keep
// the defaults, and the effective configuration can be written back next to a run's outputs.

#include <Eigen/Geometry>
#include <stdexcept>
#include <string>

#include "hylo/estimation/imu_noise.h"
#include "hylo/estimation/odometry_pipeline.h"
#include "hylo/io/log_reader.h"
#include "hylo/mapping/ground_filter.h"

namespace hylo::config {

/// A configuration that cannot be used: the message names the file, the key path and why.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The lidar stream: where it is and how its driver stamps points.
struct LidarConfig {
  std::string topic = "/points";  ///< sensor_msgs/PointCloud2 topic in a bag
  io::PointTimeConvention time_convention = io::PointTimeConvention::kAuto;  ///< per-point time
  double min_range_m = 0.5;       ///< returns closer than this are dropped (vehicle body), m
  double max_range_m = 100.0;     ///< returns farther than this are dropped, m
  double scan_period_s = 0.1;     ///< nominal sweep duration, s (10 Hz spinning lidar: 0.1)

  bool IsValid(std::string* why) const;
};

/// The inertial stream. `imu: none` in YAML disables it (no-IMU mode).
struct ImuConfig {
  bool enabled = true;            ///< false = no IMU: constant-velocity model, no deskewing
  std::string topic = "/imu";     ///< sensor_msgs/Imu topic in a bag
  double rate_hz = 200.0;         ///< nominal sample rate, Hz (used to detect gaps)
  double gravity_mps2 = 9.81;     ///< local gravity magnitude, m/s^2
  double accel_scale = 1.0;       ///< multiplies accelerations; 9.81 for drivers reporting g
  estimation::ImuNoise noise;     ///< continuous-time noise densities

  bool IsValid(std::string* why) const;
};

/// A rigid transform as written in YAML: translation and roll-pitch-yaw, R = Rz(y) Ry(p) Rx(r).
struct TransformConfig {
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();     ///< m
  Eigen::Vector3d rotation_rpy_deg = Eigen::Vector3d::Zero();  ///< roll, pitch, yaw in degrees

  Eigen::Isometry3d ToIsometry() const;
  bool IsValid(std::string* why) const;
};

/// Section `map:` — the map manager's settings plus what localization adds.
struct MapConfig : mapping::MapManagerOptions {
  double prior_resolution_m = 0.1;  ///< uniform-sampling voxel of a prior map when loaded, m
                                    ///< (0 = keep all); finer than voxel_size_m so the ICP
                                    ///< initializer's fitness gate (0.01 m²) is reachable
  double update_after_s = -1.0;     ///< hybrid mode: seconds after the localization start from
                                    ///< which scans extend the map; -1 = localization only
  bool IsValid(std::string* why) const;
};

/// Section `localization:` — start from a prior map (ICP initializer), health, relocalization.
struct LocalizationConfig {
  std::string initial_guess;  ///< "x y z roll pitch yaw" (m, deg) or 16 numbers (4×4 T_world_imu,
                              ///< row-major); empty = none (give --guess on the command line)
  estimation::LocalizationOptions options;  ///< options.update_after_s comes from map:
  bool IsValid(std::string* why) const;
};

/// What a run writes besides its trajectory and summary.
struct OutputConfig {
  double dense_map_voxel_m = 0.1;  ///< voxel of map_dense.pcd (every registered scan, uniformly
                                   ///< sampled), the input of offline map crafting, m; 0 = off
  // Frame names of the odometry outputs (odometry.csv, the ROS node), REP-105. The body is
  // the IMU: base_frame names the IMU frame (publish a static transform for another base).
  std::string map_frame = "map";        ///< the prior map's (or SLAM map's) frame
  std::string odom_frame = "odom";      ///< continuous frame; relocalization jumps go to map→odom
  std::string base_frame = "base_link"; ///< the IMU (body) frame
  bool IsValid(std::string* why) const;
};

/// Everything a run reads from its configuration file.
struct RunConfig {
  std::string backend = "ieskf";  ///< estimator back-end: ieskf | sliding_window
  LidarConfig lidar;
  ImuConfig imu;
  TransformConfig T_imu_lidar;    ///< maps points from the lidar frame to the IMU frame
  // Odometry (issue 5). lidar.min/max_range_m feed the pre-processing ranges.
  estimation::PreprocessOptions preprocess;       ///< scan clean-up and downsampling
  estimation::ImuInitializerOptions init;         ///< static IMU initialisation
  estimation::IeskfOptions ieskf;                 ///< the IESKF back-end
  estimation::SlidingWindowOptions sliding_window;  ///< the sliding-window smoother back-end
  registration::PlaneMatcherOptions planes;       ///< point-to-plane association
  MapConfig map;                                  ///< map downsampling, window, hybrid mode
  LocalizationConfig localization;                ///< prior-map localization
  OutputConfig output;                            ///< extra outputs of a run
  /// Offline ground extraction of the run's map (`hylo demo`'s chain): method smrf | csf and
  /// each back-end's options; defaults for a ground robot's map (GroundFilterOptions::
  /// ForRobotMaps: SMRF, elevation threshold 0.15 m).
  mapping::GroundFilterOptions ground = mapping::GroundFilterOptions::ForRobotMaps();

  /// Checks every section; *why names the field (with its section), value and constraint.
  bool IsValid(std::string* why) const;
  /// The streams to read from a log, as io::OpenLog takes them.
  io::LogReadOptions LogOptions() const;
  /// The odometry pipeline settings of this run (estimator, IMU, extrinsic, sections above).
  estimation::OdometryPipelineOptions PipelineOptions() const;
};

/// Parses YAML text. Throws ConfigError naming `source_name`, the key path and the reason for
/// malformed YAML, unknown keys, wrong types and invalid values (IsValid).
RunConfig ParseRunConfig(const std::string& yaml_text, const std::string& source_name);
/// Reads and parses a file (ConfigError also when the file cannot be read).
RunConfig LoadRunConfig(const std::string& path);
/// The effective configuration, every field written, loadable again by ParseRunConfig.
std::string ToYaml(const RunConfig& config);
/// Writes ToYaml(config) to `path` (ConfigError when it cannot be written).
void SaveRunConfig(const std::string& path, const RunConfig& config);

}  // namespace hylo::config
