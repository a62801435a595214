#pragma once
// One interface over every recorded log: a ROS1 bag or a ROS 2 recording (rosbag2 directory,
// sqlite3 or MCAP; a single .mcap file), lidar + IMU, or a scan folder (lidar only). Readers
// stream: one message at a time, never the whole log in memory.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"

namespace hylo::logs {

/// How a driver stamps each return. Drivers disagree; kAuto detects it from the field names.
enum class PointTimeConvention {
  kAuto,       ///< detect from PointCloud2 fields
  kVelodyne,   ///< `time`: float32, seconds after the scan start
  kOuster,     ///< `t`: uint32, nanoseconds after the scan start
  kHesai,      ///< `timestamp`: float64, absolute seconds
  kRobosense,  ///< `timestamp`: float64, absolute seconds
  kLivox,      ///< Livox PointCloud2 layout (`timestamp` float64 absolute ns, `line` as ring)
  kNone,       ///< no per-point time: every return at the scan stamp (no deskewing possible)
};

/// Name used in configuration files and printouts ("velodyne", "ouster", ...).
std::string ToString(PointTimeConvention convention);
/// Parses a configuration name; returns false for an unknown name.
bool ParsePointTimeConvention(const std::string& name, PointTimeConvention* convention);

/// Which streams to read from a log.
struct LogReadOptions {
  std::string lidar_topic = "/points";  ///< PointCloud2 topic (bags only)
  std::string imu_topic = "/imu";       ///< Imu topic (bags only); empty = do not read IMU
  PointTimeConvention time_convention = PointTimeConvention::kAuto;  ///< per-point time field
  double imu_accel_scale = 1.0;  ///< multiplies accelerations: 9.81 for drivers that report g
};

/// One message from a log, in the order the log holds them (receive order for bags).
struct LogMessage {
  enum class Kind { kImu, kScan };
  Kind kind = Kind::kImu;
  ImuSample imu;   ///< valid when kind == kImu
  LidarScan scan;  ///< valid when kind == kScan
};

/// Counted drops while reading; nothing bad in the data is silently discarded.
struct LogReadCounters {
  std::size_t imu_messages = 0;
  std::size_t scan_messages = 0;
  std::size_t dropped_non_finite_points = 0;  ///< NaN/inf coordinates removed from scans
  std::size_t dropped_non_finite_imu = 0;     ///< IMU messages with NaN/inf, skipped
  std::size_t empty_scans = 0;                ///< scans with no valid point (still delivered)
};

/// What a reader could use of a damaged log (a bag whose recording was killed, or cut short):
/// it is read up to its last complete message. Filled in while the log is read; final once
/// Next() has returned false.
struct LogRecovery {
  std::string damage;            ///< what is wrong, e.g. "no index (recording interrupted?)"
  std::string stop_reason;       ///< where reading stopped, e.g. "the last chunk is cut"
  std::size_t messages = 0;      ///< complete messages found, every topic
  int64_t first_receive_ns = 0;  ///< receive time of the first of them, ns
  int64_t last_receive_ns = 0;   ///< receive time of the last of them, ns
  uint64_t file_bytes = 0;
  uint64_t unreadable_bytes = 0;  ///< bytes after the last record read whole

  double span_s() const { return (last_receive_ns - first_receive_ns) * 1e-9; }
  /// One line, e.g. "no index (recording interrupted?): recovered 1234 messages over 56.7 s;
  /// last 890 bytes unreadable (the last chunk is cut)".
  std::string Summary() const;
};

class LogReader {
 public:
  virtual ~LogReader() = default;
  /// Reads the next message; false at the end of the log. Throws std::runtime_error naming
  /// the file on unreadable or corrupt data.
  virtual bool Next(LogMessage* message) = 0;
  virtual const LogReadCounters& counters() const = 0;
  /// The per-point time convention in use (after detection).
  virtual PointTimeConvention time_convention() const = 0;
  /// Non-null when the log is damaged and read only up to its last complete message.
  virtual const LogRecovery* recovery() const { return nullptr; }
};

/// Opens a ROS 2 recording (IsRosbag2: a directory with metadata.yaml or storage files, an MCAP
/// or sqlite3 file), a scan folder (any other directory) or a ROS1 bag (any other file). Throws
/// std::runtime_error with a one-line reason: missing path, unreadable file, missing topic
/// (listing the topics that exist).
std::unique_ptr<LogReader> OpenLog(const std::string& path, const LogReadOptions& options);

}  // namespace hylo::logs
