#pragma once
// A randomized scenario (hylo/sim/scenario.h) as files, and the run configuration a user
// would write for it:
//   session_<a|b>.bag         IMU and lidar on the preset's topics, the lidar driver's
//                             per-point time layout, the IMU driver's acceleration units
//   session_<a|b>_truth.tum   T_map_imu at every IMU stamp
//   session_<a|b>.json        manifest: the scenario's every drawn figure and the counts
//   sensor_sheet.yaml         what a user knows (SensorSheet)
//   config.yaml               config/presets/<preset>.yaml with the sheet's values (ScenarioRunConfig)
// The same scenario number gives the same bytes.

#include <functional>
#include <string>

#include "hylo/config/run_config.h"
#include "hylo/io/json.h"
#include "hylo/logs/log_writer.h"
#include "hylo/sim/scenario.h"
#include "hylo/sim/simulator.h"

namespace hylo::sim {

/// `config_dir`/<sheet.preset>.yaml with the sheet's extrinsic, IMU rate, IMU noise and clock
/// offset (lidar.time_offset_s), and no dense map output (map_dense.pcd is for crafting, not
/// odometry).
/// Throws config::ConfigError naming the preset file when it cannot be read.
config::RunConfig ScenarioRunConfig(const SensorSheet& sheet, const std::string& config_dir);

/// Every drawn figure of `scenario` (site recipe, sensor, IMU grade, mounting, motion).
io::Json ScenarioToJson(const Scenario& scenario);

/// Simulates `session` of `scenario` and writes its log in `format` (laid out as `config`
/// reads it),
/// truth and manifest into `dir` (created if missing). Throws naming the file on I/O errors.
SessionSummary WriteScenarioSession(
    const Scenario& scenario, const Site& site, SessionId session, const config::RunConfig& config,
    const std::string& dir, const std::function<void(std::size_t, std::size_t)>& progress = {},
    logs::LogFormat format = logs::LogFormat::kRos1);

/// Writes sensor_sheet.yaml and config.yaml into `dir`.
void WriteScenarioSheet(const SensorSheet& sheet, const config::RunConfig& config,
                        const std::string& dir);

}  // namespace hylo::sim
