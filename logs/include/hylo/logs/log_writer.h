#pragma once
// Writing a log in the formats hylo reads, behind one interface: a ROS1 bag, or a ROS 2
// recording (rosbag2 directory with sqlite3 or MCAP storage, MCAP chunks stored or compressed).
// The simulator and `hylo convert` write through it.

#include <cstdint>
#include <memory>
#include <string>

#include "hylo/common/sensor_data.h"
#include "hylo/logs/log_reader.h"
#include "hylo/logs/pointcloud2.h"

namespace hylo::logs {

enum class LogFormat {
  kRos1,      ///< ROS1 bag (.bag)
  kSqlite3,   ///< rosbag2 directory, sqlite3 storage (ROS 2 before Iron)
  kMcap,      ///< rosbag2 directory, MCAP storage, chunks stored (ROS 2's default since Iron)
  kMcapZstd,  ///< rosbag2 directory, MCAP storage, zstd chunks
  kMcapLz4,   ///< rosbag2 directory, MCAP storage, lz4 chunks
};

/// "ros1", "sqlite3", "mcap", "mcap-zstd", "mcap-lz4".
std::string ToString(LogFormat format);
/// Parses one of the names above; false for another.
bool ParseLogFormat(const std::string& name, LogFormat* format);
/// The log named `stem` (a path without extension) in `format`: "<stem>.bag" for ROS1, the
/// directory "<stem>" for the rosbag2 formats.
std::string LogPathFor(const std::string& stem, LogFormat format);

/// Writes messages as a driver's recording looks: each message's receive time is its stamp (a
/// scan's is its end time, when a driver publishes it), so readers get receive order. Not
/// thread-safe. Negative stamps throw std::invalid_argument.
class LogWriter {
 public:
  virtual ~LogWriter() = default;
  /// sensor_msgs Imu: header.stamp = t_ns, linear_acceleration = accel_imu (as given),
  /// angular_velocity = gyro_imu (rad/s), orientation unknown (orientation_covariance[0] = -1).
  /// Receive time = t_ns, or `receive_t_ns` when >= 0 (a late message, as tests need them).
  virtual void WriteImu(const std::string& topic, const ImuSample& imu, const std::string& frame_id,
                        int64_t receive_t_ns = -1) = 0;
  /// sensor_msgs PointCloud2 in the field layout of `layout`'s driver (EncodePointCloud2);
  /// `frame_id` replaces scan.frame_id. Receive time = scan.end_t_ns.
  virtual void WriteScan(const std::string& topic, const LidarScan& scan,
                         PointTimeConvention layout, const std::string& frame_id);
  /// Any cloud, as given (tests of odd layouts; converters). Receive time `receive_t_ns`.
  virtual void WriteCloud(const std::string& topic, const PointCloud2Message& cloud,
                          int64_t receive_t_ns) = 0;
  /// Finishes the log (index, summary, metadata); further writes throw std::logic_error.
  /// Throws std::runtime_error naming the path on an I/O error.
  virtual void Close() = 0;
};

/// A writer of `format` at `path` (a .bag file for ROS1, else a rosbag2 directory, or for the
/// MCAP formats a single file when `path` ends in ".mcap"). Throws std::runtime_error naming the
/// path when it cannot be created.
std::unique_ptr<LogWriter> CreateLogWriter(const std::string& path, LogFormat format);

}  // namespace hylo::logs
