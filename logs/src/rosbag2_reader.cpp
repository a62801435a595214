// A rosbag2 recording as a LogReader: its files merged by log time (rosbag2_stream.h), the
// lidar and IMU topics decoded from CDR (cdr_messages.h) into what every log reader delivers
// (message_decode.h).

#include "hylo/logs/rosbag2_reader.h"

#include <filesystem>
#include <stdexcept>

#include "cdr_messages.h"
#include "message_decode.h"
#include "printable.h"
#include "rosbag2_stream.h"

namespace hylo::logs {
namespace {

using detail::StorageMessage;

const std::vector<std::string> kCloudTypes = {detail::kRos2CloudType, detail::kLivoxCustomType};
const std::vector<std::string> kImuTypes = {detail::kRos2ImuType};

class Rosbag2Reader : public LogReader {
 public:
  Rosbag2Reader(const std::string& path, const LogReadOptions& options)
      : options_(options),
        convention_(options.time_convention),
        layout_(detail::ResolveRosbag2(path)),
        stream_(layout_),
        bytes_(layout_.compression_mode == "message") {
    if (stream_.topics_complete()) RequireTopics(stream_);
    Preflight();
  }

  bool Next(LogMessage* message) override {
    StorageMessage m;
    while (stream_.Next(&m)) {
      ++message_index_;
      const std::string& topic = m.topic->name;
      const bool scan = topic == options_.lidar_topic;
      if (!scan && (options_.imu_topic.empty() || topic != options_.imu_topic)) continue;
      try {
        const auto [data, size] = bytes_.Of(m);
        if (scan) {
          RequireType(*m.topic, kCloudTypes);
          detail::DecodeScan(detail::DecodeCdrCloud(m.topic->type, data, size), convention_,
                             message, &counters_);
          return true;
        }
        RequireType(*m.topic, kImuTypes);
        ImuSample imu = detail::DecodeCdrImu(data, size);
        // Some drivers (Livox) publish g instead of m/s^2; the configuration says which.
        imu.accel_imu = options_.imu_accel_scale * imu.accel_imu;
        if (detail::AcceptImu(imu, message, &counters_)) return true;
      } catch (const std::exception& e) {
        throw std::runtime_error("bag '" + layout_.path + "', topic '" + detail::Printable(topic) +
                                 "', message " + std::to_string(message_index_) + ": " + e.what());
      }
    }
    return false;
  }

  const LogReadCounters& counters() const override { return counters_; }
  PointTimeConvention time_convention() const override { return convention_; }
  const LogRecovery* recovery() const override { return stream_.recovery(); }

 private:
  void RequireType(const detail::StorageTopic& t, const std::vector<std::string>& types) const {
    detail::RequireTopic(layout_.path, {{t.name, {t.type}}}, t.name, types);
  }

  void RequireTopics(const detail::Rosbag2Stream& stream) const {
    const detail::TopicTypes topics = stream.Topics();
    detail::RequireTopic(layout_.path, topics, options_.lidar_topic, kCloudTypes);
    if (!options_.imu_topic.empty()) {
      detail::RequireTopic(layout_.path, topics, options_.imu_topic, kImuTypes);
    }
    for (const std::string& name : {options_.lidar_topic, options_.imu_topic}) {
      for (const detail::StorageTopic& t : stream.TopicEntries(name)) {
        if (!t.serialization_format.empty() && t.serialization_format != "cdr") {
          throw std::runtime_error("bag '" + layout_.path + "': topic '" + name +
                                   "' is serialized as '" +
                                   detail::Printable(t.serialization_format) + "', hylo reads cdr");
        }
      }
    }
  }

  /// Reads ahead (separately) to the first scan: it resolves kAuto and shows a cloud hylo
  /// cannot read at open. A recording without an index shows its topics only on the way there.
  void Preflight() {
    detail::Rosbag2Stream ahead(layout_);
    StorageMessage m;
    const auto imu_known = [&] {
      return options_.imu_topic.empty() || ahead.Topics().count(options_.imu_topic) > 0;
    };
    bool have_scan = false;
    while (!(have_scan && imu_known()) && ahead.Next(&m)) {
      if (have_scan || m.topic->name != options_.lidar_topic) continue;
      have_scan = true;
      RequireType(*m.topic, kCloudTypes);
      PointCloud2Message first;
      try {
        const auto [data, size] = bytes_.Of(m);
        first = detail::DecodeCdrCloud(m.topic->type, data, size);
      } catch (const std::exception& e) {
        throw std::runtime_error("bag '" + layout_.path + "', topic '" + options_.lidar_topic +
                                 "', first message: unreadable (" + e.what() + ")");
      }
      convention_ = detail::CheckFirstCloud(first, convention_, layout_.path, options_.lidar_topic);
    }
    if (!stream_.topics_complete()) RequireTopics(ahead);
    if (!have_scan && convention_ == PointTimeConvention::kAuto) {
      convention_ = PointTimeConvention::kNone;
    }
  }

  LogReadOptions options_;
  PointTimeConvention convention_;
  detail::Rosbag2Layout layout_;
  mutable detail::Rosbag2Stream stream_;
  detail::MessageBytes bytes_;
  LogReadCounters counters_;
  std::size_t message_index_ = 0;
};

}  // namespace

bool IsRosbag2(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(path, ec)) {
    return fs::is_regular_file(path, ec) && detail::HasRosbag2StorageMagic(path);
  }
  if (fs::exists(fs::path(path) / detail::kRosbag2MetadataFile, ec)) return true;
  for (const auto& entry : fs::directory_iterator(path, ec)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".mcap" || ext == ".db3")) return true;
  }
  return false;
}

std::unique_ptr<LogReader> OpenRosbag2(const std::string& path, const LogReadOptions& options) {
  return std::make_unique<Rosbag2Reader>(path, options);
}

}  // namespace hylo::logs
