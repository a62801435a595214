// A damaged bag read in file order (the order a recorder wrote it in, which is receive order)
// through BagRecordScanner; messages are deserialized with roscpp_serialization exactly as
// rosbag::MessageInstance would.

#include "bag_recovered_reader.h"

#include <stdexcept>

#include "bag_decode.h"
#include "bag_records.h"

namespace hylo::logs::detail {
namespace {

class RecoveredBagReader : public LogReader {
 public:
  RecoveredBagReader(const std::string& path, const LogReadOptions& options,
                     const std::string& damage)
      : path_(path), options_(options), convention_(options.time_convention), scanner_(path) {
    recovery_.damage = damage;
    recovery_.file_bytes = scanner_.file_bytes();
    Preflight();
  }

  bool Next(LogMessage* message) override {
    BagMessageRecord record;
    while (scanner_.Next(&record)) {
      if (recovery_.messages++ == 0) recovery_.first_receive_ns = record.receive_ns;
      recovery_.last_receive_ns = record.receive_ns;
      const std::string& topic = record.connection->topic;
      const bool scan = topic == options_.lidar_topic;
      if (!scan && (options_.imu_topic.empty() || topic != options_.imu_topic)) continue;
      try {
        if (scan) {
          RequireType(*record.connection, kCloudType);
          RequireDefinition<sensor_msgs::PointCloud2>(*record.connection);
          DecodeScan(Deserialize<sensor_msgs::PointCloud2>(record), convention_, message,
                     &counters_);
          return true;
        }
        RequireType(*record.connection, kImuType);
        RequireDefinition<sensor_msgs::Imu>(*record.connection);
        if (DecodeImu(Deserialize<sensor_msgs::Imu>(record), options_.imu_accel_scale, message,
                      &counters_)) {
          return true;
        }
      } catch (const std::exception& e) {
        throw std::runtime_error("bag '" + path_ + "', topic '" + Printable(topic) + "', message " +
                                 std::to_string(recovery_.messages) + ": " + e.what());
      }
    }
    recovery_.stop_reason = scanner_.stop_reason();
    recovery_.unreadable_bytes = scanner_.file_bytes() - scanner_.readable_bytes();
    return false;
  }

  const LogReadCounters& counters() const override { return counters_; }
  PointTimeConvention time_convention() const override { return convention_; }
  const LogRecovery* recovery() const override { return &recovery_; }

 private:
  void RequireType(const BagConnection& c, const char* type) const {
    if (c.type != type) {
      throw std::runtime_error("bag '" + path_ + "': topic '" + Printable(c.topic) + "' has type " +
                               Printable(c.type) + ", expected " + type);
    }
  }

  /// The topics the readable part holds, checked as the indexed reader checks them, and the
  /// first scan decoded: read ahead (separately) until the first scan and the IMU connection
  /// have been seen, which for a recording is its first chunk.
  void Preflight() {
    BagRecordScanner ahead(path_);
    BagMessageRecord record;
    bool have_scan = false;
    const auto imu_seen = [&] {
      if (options_.imu_topic.empty()) return true;
      for (const auto& [id, c] : ahead.connections()) {
        if (c.topic == options_.imu_topic) return true;
      }
      return false;
    };
    while (!(have_scan && imu_seen()) && ahead.Next(&record)) {
      if (have_scan || record.connection->topic != options_.lidar_topic) continue;
      have_scan = true;
      if (record.connection->type != kCloudType) break;  // RequireTopic names the type
      try {
        RequireDefinition<sensor_msgs::PointCloud2>(*record.connection);
      } catch (const std::runtime_error& e) {
        throw std::runtime_error("bag '" + path_ + "': " + e.what());
      }
      try {
        convention_ = CheckFirstScan(Deserialize<sensor_msgs::PointCloud2>(record), convention_,
                                     path_, options_.lidar_topic);
      } catch (const ros::Exception& e) {
        throw std::runtime_error("bag '" + path_ + "': unreadable PointCloud2 (" + e.what() + ")");
      }
    }
    TopicTypes topics;
    for (const auto& [id, c] : ahead.connections()) topics[c.topic].push_back(c.type);
    RequireTopic(path_, topics, options_.lidar_topic, kCloudType);
    if (!options_.imu_topic.empty()) RequireTopic(path_, topics, options_.imu_topic, kImuType);
    if (!have_scan && convention_ == PointTimeConvention::kAuto) {
      convention_ = PointTimeConvention::kNone;
    }
  }

  std::string path_;
  LogReadOptions options_;
  PointTimeConvention convention_;
  BagRecordScanner scanner_;
  LogReadCounters counters_;
  LogRecovery recovery_;
};

}  // namespace

std::unique_ptr<LogReader> OpenRecoveredBag(const std::string& path, const LogReadOptions& options,
                                            const std::string& damage) {
  return std::make_unique<RecoveredBagReader>(path, options, damage);
}

}  // namespace hylo::logs::detail
