#pragma once
// One recorded log through the odometry pipeline, with everything a run writes: the code
// behind `hylo map` (SLAM), `hylo localize` (prior map + guess, hybrid mode), `hylo compare`
// and `hylo demo`, so that every back-end's run produces the same files and summary keys.
//
// Files written into out_dir:
//   config.yaml      the effective configuration
//   trajectory.tum   T_world_imu per scan placed in the map, stamped at scan end (TUM): the
//                    finalized states (the smoother's estimate of each scan once it left the
//                    window)
//   trajectory_live.tum  the same scans' live states, as the odometry stream had them
//   trajectory_provisional.tum  the scans that were not a place in the map (a search's
//                    provisional frame, a lost vehicle), only when there were some
//   odometry.csv     per scan: pose, body twist, 6×6 pose and twist covariances, health,
//                    pose_status
//                    (column order documented in the file's header line)
//   timing.csv       per-scan timing and update figures
//   map.pcd          the final map (prior + added points, or the SLAM map), world frame
//   map_added.pcd    hybrid mode: only the points added to the prior during the run
//   map_dense.pcd    every registered scan at output.dense_map_voxel_m (0 = not written)
//   summary.json     the summary returned below
// World frame: the prior map's file frame (its local origin is added back); for SLAM the map
// frame of the run.

#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/config/run_config.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/io/json.h"
#include "hylo/logs/log_reader.h"
#include "hylo/io/trajectory_io.h"

namespace hylo::run {

struct RunRequest {
  std::string log;           ///< ROS1 bag or scan folder
  config::RunConfig config;  ///< the run's configuration (backend, sensors, ...)
  std::string prior_map;     ///< PCD/PLY prior map; empty = SLAM from scratch
  std::optional<Eigen::Isometry3d> guess_world_imu;  ///< T_world_imu guess at the start;
                                                     ///< none with prior_map: a global start
  double c2c_max_distance_m = 0.5;  ///< outlier threshold of the cloud-to-cloud metric, m
  std::string out_dir;              ///< created if missing; empty = no file is written (the
                                    ///< Python package's runs: only the returned result)
  std::string label = "run";        ///< progress label
  bool show_progress = true;        ///< progress on stderr
  /// Called after each scan enters the session with the number added so far (a front end's
  /// own progress display). What it throws ends the run and reaches the caller (cancellation).
  std::function<void(std::size_t scans_added)> on_scan;
};

/// The log was read but the pipeline gave no trajectory: its start failed (the vehicle
/// moved during the IMU initialisation, no accepted ICP start) or no scan was processed.
/// Bad data, not an unreadable file: front ends tell the two apart by this type.
class RunFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunResult {
  io::Json summary;                              ///< also written to out_dir/summary.json
  std::vector<io::StampedPose> trajectory;       ///< T_world_imu, finalized, one per scan
  std::vector<io::StampedPose> live_trajectory;  ///< T_world_imu, live, one per scan
  std::vector<double> ms_per_scan;               ///< wall time per processed scan, ms
};

/// The pipeline's counters (scans processed, skipped, not applied, queue drops and gaps) as
/// the `counters` object of summary.json; the ROS node's health topic carries the same.
io::Json PipelineCountersJson(const odometry::PipelineCounters& counters);

/// What the back-end calibrated online, as the `online_calibration` object of summary.json:
/// the clock-offset correction, its sigma and the offset to configure (lidar.time_offset_s),
/// the extrinsic rotation correction (rotation vector, IMU frame) and its sigmas, in degrees,
/// and the extrinsic translation correction (IMU frame) and its sigmas, in metres.
io::Json OnlineCalibrationJson(const estimation::OnlineCalibration& calibration,
                               double configured_time_offset_s);

/// The `online_calibration` of a run's summary as one line for the user ("" when there is
/// none): the offset to configure and the extrinsic corrections, each with its sigma.
std::string OnlineCalibrationLine(const io::Json& summary);

/// A damaged log's recovery as the `log.recovery` object of summary.json (and `hylo info`).
io::Json LogRecoveryJson(const logs::LogRecovery& recovery);

/// The IMU faults the queue dropped or noticed, and `unread_non_finite` samples the log reader
/// already dropped for NaN/inf values, as one line for the user ("" when there were none):
/// gaps (count, longest, total), duplicated and backward stamps, NaN/inf and clipped samples.
std::string ImuFaultsLine(const odometry::QueueCounters& queue, std::size_t unread_non_finite);

/// Runs the log. Throws std::runtime_error naming the file and reason for unreadable input,
/// RunFailed for a failed initialisation (vehicle moving, no accepted ICP start) or a log
/// with no scan.
RunResult RunLog(const RunRequest& request);

}  // namespace hylo::run
