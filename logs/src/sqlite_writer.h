#pragma once
// Private to hylo_logs: a rosbag2 sqlite3 database written as ROS 2 Humble's recorder writes
// one (schema version 3: tables schema, metadata, topics, messages, and the timestamp index).
// It is built under a temporary name and renamed into place at Close(), so that a writer that
// fails leaves no database behind.

#include <sqlite3.h>

#include <cstdint>
#include <memory>
#include <string>

namespace hylo::logs::detail {

class SqliteWriter {
 public:
  /// Throws std::runtime_error naming `path` when it cannot be created.
  explicit SqliteWriter(const std::string& path);
  ~SqliteWriter();  ///< removes the temporary database when Close() was not reached
  SqliteWriter(const SqliteWriter&) = delete;
  SqliteWriter& operator=(const SqliteWriter&) = delete;

  /// Returns the topic's id (1, 2, ...).
  int64_t AddTopic(const std::string& name, const std::string& type, const std::string& format,
                   const std::string& offered_qos_profiles);
  void Write(int64_t topic_id, int64_t timestamp_ns, const uint8_t* data, std::size_t size);
  /// Stores `metadata_yaml` in the metadata table (as rosbag2 does), commits and renames the
  /// database into place. Throws std::runtime_error naming the file on failure.
  void Close(int metadata_version, const std::string& metadata_yaml);

 private:
  void Execute(const std::string& sql);
  [[noreturn]] void Fail(const std::string& what) const;

  std::string path_;
  std::string temporary_;
  std::unique_ptr<sqlite3, decltype(&sqlite3_close)> db_{nullptr, &sqlite3_close};
  std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> insert_{nullptr, &sqlite3_finalize};
  int64_t topics_ = 0;
  bool closed_ = false;
};

}  // namespace hylo::logs::detail
