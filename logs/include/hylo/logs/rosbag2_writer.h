#pragma once
// ROS 2 recordings written without ROS: a rosbag2 directory (metadata.yaml version 5 and one
// storage file, sqlite3 or MCAP) that ROS 2's own tools (`ros2 bag info`, `ros2 bag play`,
// Humble onwards) read, or a single MCAP file. Messages are CDR-encoded; MCAP files carry each
// type's message definition (ros2msg schemas) and the rosbag2 profile.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hylo/logs/log_writer.h"

namespace hylo::logs {

enum class Rosbag2Storage { kSqlite3, kMcap };

struct Rosbag2WriterOptions {
  Rosbag2Storage storage = Rosbag2Storage::kMcap;  ///< sqlite3 (.db3) or MCAP (.mcap) storage
  std::string mcap_compression;                    ///< MCAP chunks: "" (stored), "zstd" or "lz4"
  uint64_t mcap_chunk_bytes = 786432;  ///< uncompressed bytes per MCAP chunk (768 KiB, rosbag2's)

  /// Names the field and the constraint when false.
  bool IsValid(std::string* why) const;
};

class Rosbag2Writer : public LogWriter {
 public:
  /// A rosbag2 directory at `path` (created if missing; it must not hold a recording) with
  /// metadata.yaml and `<name>_0.db3` or `<name>_0.mcap`, `<name>` the directory's name; with
  /// MCAP storage and a path ending in ".mcap", that one file instead. Nothing appears until
  /// Close(): a writer destroyed before leaves no recording. Throws std::invalid_argument for
  /// invalid options, std::runtime_error naming the path when it cannot be created.
  Rosbag2Writer(const std::string& path, const Rosbag2WriterOptions& options);
  ~Rosbag2Writer() override;
  Rosbag2Writer(const Rosbag2Writer&) = delete;
  Rosbag2Writer& operator=(const Rosbag2Writer&) = delete;

  void WriteImu(const std::string& topic, const ImuSample& imu, const std::string& frame_id,
                int64_t receive_t_ns = -1) override;
  void WriteCloud(const std::string& topic, const PointCloud2Message& cloud,
                  int64_t receive_t_ns) override;
  /// A message already in CDR, of ROS 2 type `type` (e.g. "livox_ros_driver2/msg/CustomMsg"):
  /// for converters and tests. A topic keeps the type of its first message
  /// (std::invalid_argument otherwise).
  void WriteCdr(const std::string& topic, const std::string& type, int64_t receive_t_ns,
                const std::vector<uint8_t>& cdr);
  void Close() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hylo::logs
