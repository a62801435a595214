#pragma once
// Writes simulated sessions and the site's ground truth to a directory:
//   session_<a|b>.bag         /imu (sensor_msgs/Imu, frame imu), /points (PointCloud2,
//                             Velodyne fields x y z intensity ring time, frame lidar); in a
//                             ROS 2 format the rosbag2 directory session_<a|b>/ instead
//   session_<a|b>_truth.tum   T_map_imu at every IMU stamp (TUM: t x y z qx qy qz qw)
//   session_<a|b>.json        manifest: seed, every option, extrinsic, noise, counts
//   site_reference.pcd        noise-free site surfaces as in session A, label 0 ground 1 object
//   site_slope.txt            true slope grid (see reference_outputs.h)
//   site.json                 the site's objects and which session holds them
// Everything is a function of the options (seed included): the same options give the same
// bytes. Wall-clock figures are returned, never written.

#include <functional>
#include <string>

#include "hylo/io/json.h"
#include "hylo/logs/log_writer.h"
#include "hylo/sim/simulator.h"

namespace hylo::sim {

/// What the site-level files need beyond SimulationOptions.
struct SiteOutputOptions {
  double reference_spacing_m = 0.1;  ///< object surface sampling of the reference cloud, m
  double slope_resolution_m = 0.5;   ///< slope grid cell, m

  bool IsValid(std::string* why) const;
};

std::string SessionBagPath(const std::string& dir, SessionId session);
/// The session's log in `format`: SessionBagPath for ROS1, the directory session_<a|b> else.
std::string SessionLogPath(const std::string& dir, SessionId session, logs::LogFormat format);
std::string SessionTruthPath(const std::string& dir, SessionId session);
std::string SessionManifestPath(const std::string& dir, SessionId session);

/// Simulates `session` and writes its log (in `format`), truth and manifest into `dir`
/// (created if missing). Throws std::runtime_error naming the file on I/O failure.
SessionSummary WriteSession(const SimulationOptions& options, const Site& site, SessionId session,
                            const std::string& dir,
                            const std::function<void(std::size_t, std::size_t)>& progress = {},
                            logs::LogFormat format = logs::LogFormat::kRos1);

/// Writes site_reference.pcd, site_slope.txt and site.json into `dir`.
void WriteSiteOutputs(const SimulationOptions& options, const Site& site,
                      const SiteOutputOptions& output, const std::string& dir);

/// Every simulation option as JSON (for manifests and --json summaries).
io::Json OptionsToJson(const SimulationOptions& options);

}  // namespace hylo::sim
