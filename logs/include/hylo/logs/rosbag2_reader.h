#pragma once
// ROS 2 recordings, read without ROS: a rosbag2 directory (metadata.yaml and one or more
// storage files, sqlite3 `.db3` or MCAP `.mcap`, split recordings in order), or a single
// `.mcap` (or `.db3`) file given directly. Messages come in log-time (receive-time) order across
// the files; sensor_msgs/msg/PointCloud2 (and livox_ros_driver2/msg/CustomMsg) and
// sensor_msgs/msg/Imu are decoded from CDR into the same scans and samples as ROS1 bags give,
// with the same per-point time conventions and counted drops.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hylo/logs/bag_reader.h"
#include "hylo/logs/log_reader.h"

namespace hylo::logs {

/// True when `path` is a directory holding metadata.yaml or .db3/.mcap files, or a file that
/// starts with the MCAP magic or the sqlite3 header.
bool IsRosbag2(const std::string& path);

/// Opens a recording for streaming, one message at a time (MCAP: about one chunk in memory).
/// Scans come from `options.lidar_topic` (PointCloud2, or a Livox CustomMsg read as the
/// PointCloud2 its driver publishes), IMU samples from `options.imu_topic`, as OpenBag reads
/// them. A recording cut short (recorder killed: an MCAP file without its summary or with its
/// last chunk cut, no metadata.yaml; a database cut short) is read to its last complete message
/// and recovery() says so. rosbag2's own compression is read when it is zstd (per message or
/// per file). Throws std::runtime_error, one line naming the path: missing path, metadata.yaml
/// malformed or naming missing storage files, an unknown storage or compression, a missing
/// topic (listing those there are), a topic of the wrong type or serialization, a cloud without
/// x/y/z. Next() throws the same way on data that turns out corrupt later.
std::unique_ptr<LogReader> OpenRosbag2(const std::string& path, const LogReadOptions& options);

/// What a recording holds.
struct Rosbag2Description {
  std::string path;
  std::string storage;             ///< "sqlite3" or "mcap"
  std::string compression;         ///< "none"; MCAP chunk codecs ("zstd", "lz4", "zstd, none");
                                   ///< rosbag2's own: "zstd (per message)", "zstd (per file)"
  int metadata_version = 0;        ///< of metadata.yaml; 0 when there is none (a single file)
  std::vector<std::string> files;  ///< storage files, in reading order
  uint64_t size_bytes = 0;         ///< of the storage files
  int64_t start_ns = 0;            ///< earliest log (receive) time
  int64_t end_ns = 0;              ///< latest log time
  double duration_s = 0.0;
  std::size_t message_count = 0;
  /// Sorted by name; stamps are log times (stamps_from_header false); PointCloud2 and Livox
  /// topics carry the first message's fields and the convention they announce.
  std::vector<BagTopicDescription> topics;
  std::optional<LogRecovery> recovery;  ///< set for a damaged recording
};

/// Describes a recording from its indexes where it has them (sqlite3 tables, MCAP summary and
/// message indexes), decoding only the first message of each point cloud topic; a damaged
/// recording from every readable message. Throws like OpenRosbag2.
Rosbag2Description DescribeRosbag2(const std::string& path);

}  // namespace hylo::logs
