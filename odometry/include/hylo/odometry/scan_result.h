#pragma once
// What the odometry pipeline hands out: one result per processed scan, and the counters of
// what it dropped or noticed over the run.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>

#include "hylo/common/point_types.h"
#include "hylo/estimation/estimator.h"
#include "hylo/localization/localization.h"
#include "hylo/odometry/measurement_queue.h"
#include "hylo/estimation/nav_state.h"

namespace hylo::odometry {

/// How far a scan's pose may be trusted.
enum class PoseStatus {
  kValid,        ///< a pose in the map (SLAM: always)
  kLost,         ///< in the map frame, but the scans stopped fitting the map: not a pose to use
  kProvisional,  ///< no place in the map yet: odometry in a provisional frame while searching
};
/// "valid", "lost", "provisional".
const char* ToString(PoseStatus status);

/// One processed scan, stamped at its end.
struct ScanResult {
  int64_t t_ns = 0;  ///< scan end, ns
  PoseStatus pose_status = PoseStatus::kValid;  ///< only kValid poses are a place in the map
  estimation::NavState state;    ///< live state after the update (see Estimator)
  estimation::PoseCovariance6 pose_covariance = estimation::PoseCovariance6::Zero();
  estimation::UpdateSummary update;        ///< without point_residuals_m: read into `health`
  std::size_t raw_points = 0;  ///< after clean-up
  std::size_t downsampled_points = 0;
  std::size_t map_points = 0;  ///< after the map update
  /// Accepted for the map: it joins the map at its finalized state (at once with the filter,
  /// when it leaves the smoother's window).
  bool map_updated = false;
  double deskew_ms = 0.0, update_ms = 0.0, map_ms = 0.0, total_ms = 0.0;  ///< wall time
  double cpu_ms = 0.0;  ///< CPU time of this thread for the whole scan (robust to a busy host)
  /// CPU time of the whole process over the scan: with `threads` > 1, this thread's and the
  /// helpers' that shared its loops (and any other thread of the process running meanwhile,
  /// e.g. a background search or the tile loader).
  double process_cpu_ms = 0.0;
  /// Body-frame twist of the IMU at t_ns: linear = R_map_imuᵀ v_map_imu (m/s), angular = the
  /// last gyro sample minus its bias (rad/s; without IMU, from the last two poses).
  Eigen::Vector3d linear_velocity_imu = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_imu = Eigen::Vector3d::Zero();
  /// 6×6 twist covariance, order [v (IMU frame, m/s); ω (IMU frame, rad/s)].
  Eigen::Matrix<double, 6, 6> twist_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  /// REP-105 odom frame: T_map_imu = T_map_odom · T_odom_imu, where T_odom_imu stays continuous
  /// and relocalization jumps go into T_map_odom (identity until the first relocalization).
  lie::SE3d T_map_odom;
  localization::ScanHealth health;  ///< fit to the map, from the update's residuals (SLAM and localization)
  /// The scan in the map frame at output.dense_map_voxel_m (empty when that option is 0 or
  /// the update was not applied: an unregistered scan must not smear a dense map).
  PointCloud registered_points_map;
};

struct PipelineCounters {
  QueueCounters queue;
  std::size_t scans_before_init = 0;  ///< dropped while the IMU initialised
  std::size_t scans_too_small = 0;    ///< fewer than preprocess.min_points
  std::size_t scans_processed = 0;
  std::size_t scans_not_applied = 0;  ///< update not applied (too few matches, ...)
  std::size_t scans_degenerate = 0;
  std::size_t points_dropped_sanitize = 0;
  std::size_t scans_initializer = 0;  ///< consumed by the ICP initializer (start, relocalization)
  std::size_t scans_bad_health = 0;   ///< localization: scans whose ScanHealth was not good
};

}  // namespace hylo::odometry
