#pragma once
// ROS1 bag reading (rosbag_storage, no ROS runtime): a streaming LogReader over one
// sensor_msgs/PointCloud2 topic and one sensor_msgs/Imu topic, and a description of a bag's
// topics for `hylo info`.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hylo/logs/log_reader.h"
#include "hylo/logs/pointcloud2.h"

namespace hylo::logs {

/// Opens a bag for streaming in bag (receive-time) order; messages are read one at a time
/// through rosbag::View, never the whole bag. A bag v2.0 whose index cannot be read (the
/// recording was killed: no index, the last chunk never closed; or the file was cut short) is
/// read record by record in file order up to its last complete message; the reader's
/// recovery() then says what was recovered and how many bytes at the end were unreadable. Scans
/// come from `options.lidar_topic` (PointCloud2, decoded with `options.time_convention`; kAuto is
/// resolved on the first scan, here at open), IMU samples from `options.imu_topic` (Imu:
/// linear_acceleration -> accel_imu, angular_velocity -> gyro_imu, header.stamp -> t_ns). NaN/inf
/// points are dropped and counted; empty scans are delivered and counted; IMU messages with NaN/inf
/// are skipped and counted. Throws std::runtime_error, one line naming the file, when the bag is
/// missing or not a bag, a topic is missing (listing the topics that exist with their types), a
/// topic has the wrong type, or a cloud lacks x/y/z. Next() throws the same way on data that turns
/// out corrupt later in the bag.
std::unique_ptr<LogReader> OpenBag(const std::string& path, const LogReadOptions& options);

/// One topic of a bag.
struct BagTopicDescription {
  std::string name;                 ///< topic name
  std::string type;                 ///< message type, e.g. "sensor_msgs/Imu"
  std::size_t message_count = 0;    ///< messages on the topic
  double mean_rate_hz = 0.0;        ///< (count - 1) / (last - first stamp); 0 if undefined
  int64_t first_stamp_ns = 0;       ///< header.stamp of the first message (Imu, PointCloud2),
                                    ///< receive time for other types
  int64_t last_stamp_ns = 0;        ///< the same for the last message
  bool stamps_from_header = false;  ///< true when the stamps above are header stamps
  /// PointCloud2 topics: the first message's fields and the convention they announce.
  std::vector<PointFieldInfo> point_fields;
  PointTimeConvention detected_convention = PointTimeConvention::kNone;
};

/// What a bag holds.
struct BagDescription {
  std::string path;
  uint64_t file_size_bytes = 0;
  int64_t start_ns = 0;     ///< earliest receive time in the bag
  int64_t end_ns = 0;       ///< latest receive time in the bag
  double duration_s = 0.0;  ///< end - start, s
  std::size_t message_count = 0;
  std::vector<BagTopicDescription> topics;  ///< sorted by name
  /// Set for a bag whose index cannot be read: described from its readable records.
  std::optional<LogRecovery> recovery;
};

/// Describes a bag from its index, deserializing only the first and last message of the
/// Imu and PointCloud2 topics; a bag whose index cannot be read from every complete record
/// (all are read), with `recovery` set. Throws std::runtime_error naming the file when the bag
/// is missing or not a bag.
BagDescription DescribeBag(const std::string& path);

}  // namespace hylo::logs
