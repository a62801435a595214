// Streaming LogReader over a ROS1 bag: rosbag::View walks the bag's index in receive-time
// order and each message is deserialized only when Next() reaches it, so memory stays at
// about one chunk plus one message whatever the bag's size.

#include "hylo/io/bag_reader.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>

#include <map>
#include <stdexcept>

#include "bag_open.h"
#include "hylo/io/ros_bridge.h"

namespace hylo::io {
namespace {

constexpr char kImuType[] = "sensor_msgs/Imu";
constexpr char kCloudType[] = "sensor_msgs/PointCloud2";

/// topic -> types of its connections (normally exactly one).
using TopicTypes = std::map<std::string, std::vector<std::string>>;

TopicTypes ListTopics(const rosbag::Bag& bag) {
  TopicTypes topics;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections()) {
    topics[c->topic].push_back(c->datatype);
  }
  return topics;
}

std::string Describe(const TopicTypes& topics) {
  std::string out;
  for (const auto& [topic, types] : topics) {
    out += (out.empty() ? "" : ", ") + topic + " (" + types.front() + ")";
  }
  return out.empty() ? "none" : out;
}

void RequireTopic(const std::string& path, const TopicTypes& topics, const std::string& topic,
                  const std::string& type) {
  const auto it = topics.find(topic);
  if (it == topics.end()) {
    throw std::runtime_error("bag '" + path + "': no topic '" + topic + "' (" + type +
                             "); topics in the bag: " + Describe(topics));
  }
  for (const std::string& found : it->second) {
    if (found != type) {
      throw std::runtime_error("bag '" + path + "': topic '" + topic + "' has type " + found +
                               ", expected " + type);
    }
  }
}

class BagReader : public LogReader {
 public:
  BagReader(const std::string& path, const LogReadOptions& options)
      : path_(path), options_(options), convention_(options.time_convention) {
    detail::OpenForReading(path, &bag_);
    try {
      const TopicTypes topics = ListTopics(bag_);
      RequireTopic(path_, topics, options_.lidar_topic, kCloudType);
      std::vector<std::string> wanted = {options_.lidar_topic};
      if (!options_.imu_topic.empty()) {
        RequireTopic(path_, topics, options_.imu_topic, kImuType);
        wanted.push_back(options_.imu_topic);
      }
      CheckFirstScan();
      view_ = std::make_unique<rosbag::View>(bag_, rosbag::TopicQuery(wanted));
      it_ = view_->begin();
    } catch (const rosbag::BagException& e) {
      throw std::runtime_error("bag '" + path_ + "': corrupt or truncated (" + e.what() + ")");
    }
  }

  bool Next(LogMessage* message) override {
    while (it_ != view_->end()) {
      ++message_index_;
      bool delivered = false;
      std::string topic;
      try {
        const rosbag::MessageInstance& m = *it_;  // valid until ++it_
        topic = m.getTopic();
        delivered = topic == options_.lidar_topic ? ReadScan(m, message) : ReadImu(m, message);
        ++it_;
      } catch (const std::exception& e) {
        throw std::runtime_error("bag '" + path_ + "', topic '" + topic + "', message " +
                                 std::to_string(message_index_) + ": " + e.what());
      }
      if (delivered) return true;
    }
    return false;
  }

  const LogReadCounters& counters() const override { return counters_; }
  PointTimeConvention time_convention() const override { return convention_; }

 private:
  /// Decodes the first scan once: resolves kAuto and reports a cloud without x/y/z (or
  /// without the configured time field) at open rather than somewhere into the run.
  void CheckFirstScan() {
    rosbag::View scans(bag_, rosbag::TopicQuery(options_.lidar_topic));
    if (scans.begin() == scans.end()) {
      if (convention_ == PointTimeConvention::kAuto) convention_ = PointTimeConvention::kNone;
      return;
    }
    if (!scans.begin()->isType<sensor_msgs::PointCloud2>()) {
      throw std::runtime_error("bag '" + path_ + "': unreadable PointCloud2");
    }
    PointCloud2Message cloud =
        ros_bridge::FromRos(detail::ReadMessage<sensor_msgs::PointCloud2>(*scans.begin()));
    if (convention_ == PointTimeConvention::kAuto) {
      convention_ = DetectPointTimeConvention(cloud.fields);
    }
    try {
      DecodePointCloud2(cloud, convention_, nullptr);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("bag '" + path_ + "', topic '" + options_.lidar_topic +
                               "', first message: " + e.what());
    }
  }

  bool ReadScan(const rosbag::MessageInstance& m, LogMessage* message) {
    if (!m.isType<sensor_msgs::PointCloud2>()) {
      throw std::runtime_error("unreadable PointCloud2 on " + m.getTopic());
    }
    message->kind = LogMessage::Kind::kScan;
    message->scan =
        DecodePointCloud2(ros_bridge::FromRos(detail::ReadMessage<sensor_msgs::PointCloud2>(m)),
                          convention_, &counters_.dropped_non_finite_points);
    ++counters_.scan_messages;
    if (message->scan.points.empty()) ++counters_.empty_scans;
    return true;
  }

  /// False for a sample with NaN/inf values: skipped and counted.
  bool ReadImu(const rosbag::MessageInstance& m, LogMessage* message) {
    if (!m.isType<sensor_msgs::Imu>()) {
      throw std::runtime_error("unreadable Imu on " + m.getTopic());
    }
    // Some drivers (Livox) publish g instead of m/s^2; the configuration says which.
    message->imu =
        ros_bridge::FromRos(detail::ReadMessage<sensor_msgs::Imu>(m), options_.imu_accel_scale);
    const ImuSample& imu = message->imu;
    if (!imu.accel_imu.allFinite() || !imu.gyro_imu.allFinite()) {
      ++counters_.dropped_non_finite_imu;
      return false;
    }
    message->kind = LogMessage::Kind::kImu;
    ++counters_.imu_messages;
    return true;
  }

  std::string path_;
  LogReadOptions options_;
  PointTimeConvention convention_;
  rosbag::Bag bag_;
  std::unique_ptr<rosbag::View> view_;  // after bag_: destroyed before it
  rosbag::View::iterator it_;
  LogReadCounters counters_;
  std::size_t message_index_ = 0;
};

}  // namespace

std::unique_ptr<LogReader> OpenBag(const std::string& path, const LogReadOptions& options) {
  return std::make_unique<BagReader>(path, options);
}

}  // namespace hylo::io
