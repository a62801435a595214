#pragma once
// The two measurements every part of hylo exchanges: an inertial sample and a lidar sweep.
// Readers (logs/, io/), the simulator (sim/), the ROS node and the estimators all speak these, so
// they live at the bottom of the dependency graph. Time is int64 ns (common/time.h).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"

namespace hylo {

/// One inertial sample, in the IMU frame.
struct ImuSample {
  int64_t t_ns = 0;                                     ///< stamp, ns
  Eigen::Vector3d accel_imu = Eigen::Vector3d::Zero();  ///< specific force, m/s^2
  Eigen::Vector3d gyro_imu = Eigen::Vector3d::Zero();   ///< angular rate, rad/s
};

/// One lidar sweep. Each point carries its own time offset from `t_ns`, so the sweep can be
/// undistorted; `end_t_ns` is the latest return (or start + scan period if unknown).
struct LidarScan {
  int64_t t_ns = 0;      ///< time of the first return (scan start), ns
  int64_t end_t_ns = 0;  ///< time of the last return, ns
  std::string frame_id;  ///< the driver's frame name, for messages
  std::vector<ScanPoint> points;
};

}  // namespace hylo
