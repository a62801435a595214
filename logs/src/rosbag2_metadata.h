#pragma once
// Private to hylo_logs: a rosbag2 recording's metadata.yaml, as rosbag2 writes it (versions 1-9:
// compression fields from 3, QoS profiles from 4, the per-file list from 5, custom data from 6,
// type description hashes from 7, the ROS distribution from 8). Reading keeps what hylo uses and
// tolerates the rest; writing produces version 5, the newest one every ROS 2 distribution still
// in use (Humble onwards) reads.

#include <cstdint>
#include <string>
#include <vector>

namespace hylo::logs::detail {

constexpr char kRosbag2MetadataFile[] = "metadata.yaml";

struct Rosbag2TopicInfo {
  std::string name;
  std::string type;                  ///< e.g. "sensor_msgs/msg/Imu"
  std::string serialization_format;  ///< "cdr"
  std::string offered_qos_profiles;  ///< YAML text, as recorded
  uint64_t message_count = 0;
};

struct Rosbag2FileInfo {
  std::string path;  ///< relative to the recording's directory
  int64_t starting_time_ns = 0;
  int64_t duration_ns = 0;
  uint64_t message_count = 0;
};

struct Rosbag2Metadata {
  int version = 0;
  std::string storage_identifier;                ///< "sqlite3" or "mcap"
  std::vector<std::string> relative_file_paths;  ///< storage files, in split order
  int64_t starting_time_ns = 0;
  int64_t duration_ns = 0;
  uint64_t message_count = 0;
  std::vector<Rosbag2TopicInfo> topics;
  std::string compression_format;  ///< "" or "zstd"
  std::string compression_mode;    ///< "", "file" or "message"
  std::vector<Rosbag2FileInfo> files;
};

/// Parses metadata.yaml text. Throws std::runtime_error, one line naming `source` and the key,
/// for malformed YAML, a missing required key (version, storage_identifier,
/// relative_file_paths, topics_with_message_count and each topic's name and type) or a value of
/// the wrong type.
Rosbag2Metadata ParseRosbag2Metadata(const std::string& yaml_text, const std::string& source);

/// Reads and parses `path` (std::runtime_error naming it when it cannot be read).
Rosbag2Metadata ReadRosbag2Metadata(const std::string& path);

/// The metadata as rosbag2 writes version 5.
std::string Rosbag2MetadataYaml(const Rosbag2Metadata& metadata);

}  // namespace hylo::logs::detail
