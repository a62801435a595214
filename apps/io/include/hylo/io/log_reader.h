#pragma once
// One interface over every recorded log: a ROS1 bag (lidar + IMU) or a scan folder (lidar
// only). Readers stream: one message at a time, never the whole log in memory.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"

namespace hylo::io {

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

class LogReader {
 public:
  virtual ~LogReader() = default;
  /// Reads the next message; false at the end of the log. Throws std::runtime_error naming
  /// the file on unreadable or corrupt data.
  virtual bool Next(LogMessage* message) = 0;
  virtual const LogReadCounters& counters() const = 0;
  /// The per-point time convention in use (after detection).
  virtual PointTimeConvention time_convention() const = 0;
};

/// Opens a bag (file) or a scan folder (directory). Throws std::runtime_error with a one-line
/// reason: missing path, unreadable file, missing topic (listing the topics that exist).
std::unique_ptr<LogReader> OpenLog(const std::string& path, const LogReadOptions& options);

}  // namespace hylo::io
