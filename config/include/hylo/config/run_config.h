#pragma once
// One YAML file configures a run. This is the only place where YAML becomes the libraries'
// option structs: the YAML sections map straight onto them (the pipeline's members are named
// after the sections), each struct validates its own fields, unknown keys are errors naming
// the key path (with the new place of a key that moved), missing keys keep the defaults, and
// the effective configuration can be written back next to a run's outputs.

#include <Eigen/Geometry>
#include <stdexcept>
#include <string>

#include "hylo/inspection/planner.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/logs/log_reader.h"
#include "hylo/mapping/prior_map.h"
#include "hylo/terrain/ground_filter.h"

namespace hylo::config {

/// A configuration that cannot be used: the message names the file, the key path and why.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Where the lidar stream is in a log and how its driver stamps points (section `lidar:`).
struct LidarStream {
  std::string topic = "/points";  ///< sensor_msgs/PointCloud2 topic in a bag
  logs::PointTimeConvention time_convention = logs::PointTimeConvention::kAuto;  ///< per-point time

  bool IsValid(std::string* why) const;
};

/// Where the IMU stream is in a log and its units (section `imu:`, beside the estimator's
/// estimation::ImuOptions: rate, gravity, noise).
struct ImuStream {
  std::string topic = "/imu";  ///< sensor_msgs/Imu topic in a bag
  double accel_scale = 1.0;    ///< multiplies accelerations: 1 for m/s², about gravity_mps2
                               ///< for drivers that report g (Livox)

  /// `gravity_mps2`: the local gravity the accel scale of a g-reporting driver must match.
  bool IsValid(double gravity_mps2, std::string* why) const;
};

/// A rigid transform as written in YAML: translation and roll-pitch-yaw, R = Rz(y) Ry(p) Rx(r).
struct TransformConfig {
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();     ///< m
  Eigen::Vector3d rotation_rpy_deg = Eigen::Vector3d::Zero();  ///< roll, pitch, yaw in degrees

  Eigen::Isometry3d ToIsometry() const;
  bool IsValid(std::string* why) const;
};

/// Frame names of the odometry outputs (section `output:`, beside the pipeline's dense map
/// voxel), REP-105. The body is the IMU: base_frame names the IMU frame (publish a static
/// transform for another base).
struct OutputFrames {
  std::string map_frame = "map";        ///< the prior map's (or SLAM map's) frame
  std::string odom_frame = "odom";      ///< continuous frame; relocalization jumps go to map→odom
  std::string base_frame = "base_link"; ///< the IMU (body) frame
  bool IsValid(std::string* why) const;
};

/// Everything a run reads from its configuration file.
struct RunConfig {
  /// The library defaults, but for what a run writes by default: map_dense.pcd at 0.1 m.
  RunConfig();

  /// Every library setting; its members are the YAML sections (see OdometryPipelineOptions).
  /// Its extrinsic is taken from T_imu_lidar below (PipelineOptions).
  odometry::OdometryPipelineOptions pipeline;
  LidarStream lidar;
  ImuStream imu;
  TransformConfig T_imu_lidar;         ///< maps points from the lidar frame to the IMU frame
  mapping::PriorMapOptions prior_map;  ///< how a prior map is thinned when loaded
  std::string initial_guess;  ///< localization.initial_guess: "x y z roll pitch yaw" (m, deg) or
                              ///< 16 numbers (4×4 T_world_imu, row-major); empty = none
  OutputFrames output;
  /// Offline ground extraction of the run's map (`hylo demo`'s chain): method smrf | csf and
  /// each back-end's options; defaults for a ground robot's map (GroundFilterOptions::
  /// ForRobotMaps: SMRF, elevation threshold 0.10 m).
  terrain::GroundFilterOptions ground = terrain::GroundFilterOptions::ForRobotMaps();
  /// Inspection planning on the run's crafted map and costmap (`hylo inspect --config`,
  /// `hylo demo`): camera, ranges, voxels and clearance, robot radius, viewpoint score, tour.
  inspection::InspectionOptions inspection;

  /// Checks every section; *why names the key path, the value and the constraint.
  bool IsValid(std::string* why) const;
  /// The streams to read from a log, as logs::OpenLog takes them.
  logs::LogReadOptions LogOptions() const;
  /// The odometry pipeline's settings: `pipeline` with the extrinsic of T_imu_lidar.
  odometry::OdometryPipelineOptions PipelineOptions() const;
  /// "ieskf" / "sliding_window".
  std::string BackendName() const;
};

/// Parses YAML text. Throws ConfigError naming `source_name`, the key path and the reason for
/// malformed YAML, unknown keys, wrong types and invalid values (IsValid).
RunConfig ParseRunConfig(const std::string& yaml_text, const std::string& source_name);
/// Reads and parses a file (ConfigError also when the file cannot be read).
RunConfig LoadRunConfig(const std::string& path);
/// YAML text: `base` with every key of `overrides` set (maps merged key by key, any other
/// value replaced), scalars kept as written, so a preset changed in a few keys parses to the
/// same values as the preset itself. Throws ConfigError naming `source_name` when either text
/// is malformed or not a map.
std::string MergeYaml(const std::string& base, const std::string& overrides,
                      const std::string& source_name);
/// The keys of a `ground:` section alone (method, smrf, csf) applied to `defaults`: the same
/// keys, errors and validation as that section of a run configuration. Throws ConfigError
/// naming `source_name` and the key path (ground.smrf.cell_m, ...).
terrain::GroundFilterOptions ParseGroundOptions(const std::string& yaml_text,
                                                const std::string& source_name,
                                                terrain::GroundFilterOptions defaults);
/// The effective configuration, every field written, loadable again by ParseRunConfig.
std::string ToYaml(const RunConfig& config);
/// Writes ToYaml(config) to `path` (ConfigError when it cannot be written).
void SaveRunConfig(const std::string& path, const RunConfig& config);

}  // namespace hylo::config
