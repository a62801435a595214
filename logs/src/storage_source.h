#pragma once
// Private to hylo_logs: one storage file of a rosbag2 recording (an MCAP file or a sqlite3
// database) as a stream of raw messages in log-time order; the rosbag2 reader merges the files
// of a split recording and decodes the messages it wants.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "hylo/logs/log_reader.h"

namespace hylo::logs::detail {

/// A topic as a storage file names it.
struct StorageTopic {
  std::string name;
  std::string type;                  ///< e.g. "sensor_msgs/msg/Imu"
  std::string serialization_format;  ///< "cdr" for ROS 2
};

/// One message; `data` stays valid until the next call of the source that gave it.
struct StorageMessage {
  const StorageTopic* topic = nullptr;
  int64_t log_time_ns = 0;  ///< when the recorder received it
  const uint8_t* data = nullptr;
  std::size_t size = 0;
};

/// Messages of one topic in one file.
struct TopicStatistics {
  std::string type;
  uint64_t count = 0;
  int64_t first_ns = std::numeric_limits<int64_t>::max();  ///< earliest log time
  int64_t last_ns = std::numeric_limits<int64_t>::min();   ///< latest log time
};

/// Adds `from` to `to`, topic by topic.
inline void MergeStatistics(const std::map<std::string, TopicStatistics>& from,
                            std::map<std::string, TopicStatistics>* to) {
  for (const auto& [name, s] : from) {
    TopicStatistics& t = (*to)[name];
    if (t.type.empty()) t.type = s.type;
    t.count += s.count;
    t.first_ns = s.first_ns < t.first_ns ? s.first_ns : t.first_ns;
    t.last_ns = s.last_ns > t.last_ns ? s.last_ns : t.last_ns;
  }
}

class StorageSource {
 public:
  virtual ~StorageSource() = default;
  /// The next message in log-time order (ties: the file's order); false at the end, or where a
  /// damaged file stops being readable (recovery() then says so). Throws std::runtime_error
  /// naming the file on data that is corrupt in a file that is not damaged otherwise.
  virtual bool Next(StorageMessage* message) = 0;
  /// The topics known so far: all of them for an indexed file, those met so far for a file read
  /// record by record (topics_complete() false).
  virtual std::vector<StorageTopic> Topics() const = 0;
  virtual bool topics_complete() const = 0;
  /// Non-null for a damaged file (recording killed, file cut): what is wrong; final once Next()
  /// has returned false. `messages` and the times count what this file yielded.
  virtual const LogRecovery* recovery() const = 0;
  virtual const std::string& path() const = 0;
  virtual uint64_t file_bytes() const = 0;
  /// Adds every topic's count and log-time span from the file's indexes (sqlite3 tables, MCAP
  /// message indexes) to `stats`, without reading the messages; false (nothing added) when the
  /// file has no usable index. Call before Next().
  virtual bool IndexedStatistics(std::map<std::string, TopicStatistics>* stats) = 0;
  /// MCAP chunk compressions ("" for stored chunks): all of an indexed file's, else those met.
  virtual std::set<std::string> ChunkCompressions() const { return {}; }
};

/// An MCAP file: through its summary when it has one, else record by record. Throws
/// std::runtime_error naming the file when it is missing or not MCAP.
std::unique_ptr<StorageSource> OpenMcapSource(const std::string& path);

/// A rosbag2 sqlite3 database (any schema version rosbag2 has written). Throws
/// std::runtime_error naming the file when it is missing or not a rosbag2 database.
std::unique_ptr<StorageSource> OpenSqliteSource(const std::string& path);

}  // namespace hylo::logs::detail
