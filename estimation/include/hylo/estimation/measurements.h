#pragma once
// Sensor measurements as the estimators consume them. Time is int64 ns (see common/time.h).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/registration/point_types.h"

namespace hylo::estimation {

/// One inertial sample, in the IMU frame.
struct ImuSample {
  int64_t t_ns = 0;                                      ///< stamp, ns
  Eigen::Vector3d accel_imu = Eigen::Vector3d::Zero();   ///< specific force, m/s^2
  Eigen::Vector3d gyro_imu = Eigen::Vector3d::Zero();    ///< angular rate, rad/s
};

/// One lidar sweep. Each point carries its own time offset from `t_ns`, so the sweep can be
/// undistorted; `end_t_ns` is the latest return (or start + scan period if unknown).
struct LidarScan {
  int64_t t_ns = 0;        ///< time of the first return (scan start), ns
  int64_t end_t_ns = 0;    ///< time of the last return, ns
  std::string frame_id;    ///< the driver's frame name, for messages
  std::vector<registration::ScanPoint> points;
};

/// What SanitizeScan removed, for the per-run counters.
struct ScanSanitizeReport {
  std::size_t dropped_non_finite = 0;   ///< NaN or inf coordinates
  std::size_t dropped_out_of_range = 0; ///< closer than min or farther than max range
  std::size_t dropped_bad_time = 0;     ///< negative offsets or offsets beyond max_offset_ns
};

/// Drops non-finite points, points outside [min_range_m, max_range_m] and points whose time
/// offset is negative or above `max_offset_ns`; then sets end_t_ns from the remaining points
/// (or to t_ns when none remain). Never throws on bad data: it counts.
ScanSanitizeReport SanitizeScan(LidarScan* scan, float min_range_m, float max_range_m,
                                int64_t max_offset_ns);

}  // namespace hylo::estimation
