#pragma once
// A randomized scenario: from one number N (its seed), everything an estimator could be
// tuned to is drawn anew: the site (yard size, lanes, structure density, hills, trenches,
// bumps, vegetation-like clutter, a long featureless spur), the lidar (five kinds of head and
// a non-repetitive rosette), the IMU (tactical to consumer grade: noise densities, bias
// random walk and instability, scale and axis errors, local gravity, rate), how both are
// mounted (the IMU in any orientation, the lidar up to 0.5 m away), the vehicle (0.5-3 m/s,
// suspension shake, engine vibration, a start on a slope up to 20 deg) and a constant
// lidar/IMU clock offset. The same N gives the same scenario, bit for bit.
//
// A user would configure a run from the scenario's SensorSheet: the driver's preset, the
// extrinsic from the mounting drawing, the IMU noise from its datasheet, and the clock offset
// from the synchronisation's calibration, each to the precision such documents give.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/sim/imu_model.h"
#include "hylo/sim/scan_pattern.h"
#include "hylo/sim/site_layout.h"
#include "hylo/sim/trajectory.h"

namespace hylo::sim {

/// How the scenario's site is laid out (the layout itself is drawn from the same seed).
struct SiteRecipe {
  Eigen::Vector2d yard_size_m = Eigen::Vector2d(90.0, 60.0);  ///< fenced yard along x, y, m
  Eigen::Vector2d bay_m = Eigen::Vector2d(18.0, 18.0);  ///< lane spacing along x, y (nominal), m
  double structure_density = 0.5;         ///< share of the bays between lanes holding equipment
  double clutter_per_100m2 = 0.2;         ///< vegetation clumps per 100 m^2 of free ground
  int hills = 2;                          ///< hills and hollows (up to ~17 deg flanks)
  int trenches = 1;                       ///< sharp-walled cable trenches
  int bumps = 2;                          ///< short bumps on the lanes
  double undulation_m = 0.2;              ///< amplitude of the gentle undulation, m
  double undulation_wavelength_m = 25.0;  ///< its wavelength, m
  double gravel_sigma_m = 0.015;          ///< gravel roughness, m
  double featureless_m = 0.0;      ///< length of an empty spur the mapping drive takes, m (0: none)
  double start_slope_deg = 0.0;    ///< ground slope under the mapping drive's start, deg
  double route_a_m = 200.0;        ///< mapping drive, m (the spur included)
  double route_b_m = 100.0;        ///< localization drive, over lanes the mapping drive took, m
  double changed_fraction = 0.05;  ///< clutter present in only one of the two sessions
};

/// The IMU beyond sim::ImuOptions (white noise, random walk, turn-on bias, rate, gravity).
struct ImuGrade {
  ImuOptions base;
  double grade = 0.5;  ///< 0 = tactical .. 1 = consumer MEMS (what the figures were drawn from)
  double accel_bias_instability_mps2 = 0.0;  ///< first-order Gauss-Markov bias, 1 sigma, m/s^2
  double gyro_bias_instability_radps = 0.0;  ///< ... rad/s
  double bias_correlation_s = 100.0;         ///< its correlation time, s (> 0)
  double accel_scale_sigma = 0.0;  ///< scale factor error per axis, 1 sigma (1e-3 = 0.1 %)
  double gyro_scale_sigma = 0.0;
  double misalignment_sigma_rad = 0.0;  ///< axis non-orthogonality, 1 sigma, rad

  /// "tactical", "industrial" or "consumer".
  std::string Label() const;
};

/// Engine and track vibration: sums of sinusoids, faded in over `ramp_s` once the vehicle
/// starts moving (the initial rest stays exact). C-infinity, so the IMU sees it exactly.
struct Vibration {
  struct Tone {
    double frequency_hz = 20.0;
    Eigen::Vector3d amplitude = Eigen::Vector3d::Zero();  ///< m (translation) or rad (rotation)
    Eigen::Vector3d phase_rad = Eigen::Vector3d::Zero();
  };
  std::vector<Tone> translation;  ///< of the IMU, map axes
  std::vector<Tone> rotation;     ///< small rotation of the body, body axes
  double ramp_s = 1.0;            ///< fade-in, s
};

struct Scenario {
  uint64_t number = 0;  ///< the seed: everything random derives from it
  SiteRecipe site;
  SensorSpec lidar;
  /// True extrinsic: maps lidar points into the IMU frame.
  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();
  /// How the IMU sits on the vehicle (the vehicle's x forward, z up): any rotation.
  Eigen::Matrix3d R_vehicle_imu = Eigen::Matrix3d::Identity();
  int64_t lidar_time_offset_ns = 0;  ///< lidar stamp minus IMU stamp of the same instant, ns
  ImuGrade imu;
  TrajectoryOptions trajectory;  ///< speed, accelerations, suspension shake
  Vibration vibration;
  double max_drive_a_s = 120.0;  ///< the mapping drive stops after this much driving, s
  double max_drive_b_s = 60.0;   ///< ... the localization drive, s
  double terrain_resolution_m = 0.2;
  double index_cell_m = 2.0;
  int64_t start_a_ns = 1'700'000'000'000'000'000;  ///< stamp of the mapping drive's start, ns
  int64_t start_b_ns = 1'700'086'400'000'000'000;  ///< ... of the localization drive, ns

  /// One line: sensor, IMU grade, speed, slope, spur, clock offset.
  std::string Summary() const;
};

/// Scenario `number`. The sensor cycles through AllSensorKinds() every 12 numbers (each kind
/// on an even and an odd number), everything else is drawn.
Scenario DrawScenario(uint64_t number);

/// The site of a scenario with both drives' waypoints (site frame = map frame, the fenced
/// yard spans [0, yard_size_m]). Depends on the vehicle's motion only when the mapping drive
/// is cut short by max_drive_a_s (the localization drive keeps to the lanes it covered).
Site BuildScenarioSite(const Scenario& scenario);

/// One factor of a scenario that can be set to an easy value, to tell which one made a
/// scenario hard (the rest of the scenario is kept).
enum class ScenarioFactor {
  kImuGrade,     ///< a tactical IMU without scale errors or bias instability
  kSpeed,        ///< 1 m/s with gentle accelerations
  kVibration,    ///< no engine vibration, no suspension shake
  kMounting,     ///< IMU axes on the vehicle's, lidar upright 0.1 m above it
  kClockOffset,  ///< synchronised clocks
  kStartSlope,   ///< a level start
  kFeatureless,  ///< no empty spur (the mapping route differs from there on)
  kSensor,       ///< a VLP-16
};
std::vector<ScenarioFactor> AllScenarioFactors();
/// "imu_grade", "speed", ...
std::string ToString(ScenarioFactor factor);
/// `scenario` with `factor` set to its easy value.
Scenario Eased(const Scenario& scenario, ScenarioFactor factor);

/// What a user would configure from the scenario's documents: the driver preset, the
/// extrinsic from the mounting drawing (1 mm, 0.1 deg), the IMU datasheet's noise (two
/// significant digits), and the clock offset from the synchronisation's calibration (1 ms).
/// Not on the sheet (unknown to the user): local gravity, turn-on biases, bias instability,
/// scale and axis errors, vibration.
struct SensorSheet {
  uint64_t scenario = 0;
  std::string sensor;                                          ///< ToString(SensorKind)
  std::string preset;                                          ///< config/presets/<preset>.yaml
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();     ///< T_imu_lidar, m
  Eigen::Vector3d rotation_rpy_deg = Eigen::Vector3d::Zero();  ///< R = Rz(y) Ry(p) Rx(r), deg
  double imu_rate_hz = 200.0;
  double gyro_noise_density = 0.0;      ///< rad/s/sqrt(Hz)
  double accel_noise_density = 0.0;     ///< m/s^2/sqrt(Hz)
  double gyro_bias_random_walk = 0.0;   ///< rad/s^2/sqrt(Hz)
  double accel_bias_random_walk = 0.0;  ///< m/s^3/sqrt(Hz)
  double lidar_time_offset_s = 0.0;     ///< lidar stamp minus IMU stamp of one instant, s

  /// The sheet as commented YAML (the keys of a run configuration where there is one).
  std::string ToYaml() const;
};
SensorSheet SheetOf(const Scenario& scenario);

}  // namespace hylo::sim
