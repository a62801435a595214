// Streaming LogReader over a ROS1 bag: rosbag::View walks the bag's index in receive-time
// order and each message is deserialized only when Next() reaches it, so memory stays at
// about one chunk plus one message whatever the bag's size. A bag without a readable index is
// read record by record instead (bag_recovered_reader.cpp).

#include "hylo/logs/bag_reader.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <stdexcept>

#include "bag_decode.h"
#include "bag_open.h"
#include "bag_recovered_reader.h"

namespace hylo::logs {
namespace {

detail::TopicTypes ListTopics(const rosbag::Bag& bag) {
  detail::TopicTypes topics;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections()) {
    topics[c->topic].push_back(c->datatype);
  }
  return topics;
}

class BagReader : public LogReader {
 public:
  BagReader(const std::string& path, const LogReadOptions& options)
      : path_(path), options_(options), convention_(options.time_convention) {}

  /// Opens the bag through its index; false with what is wrong in `*damage` when its index
  /// cannot be read (detail::OpenIndexed). rosbag::Bag cannot be moved once open (its
  /// streams point at its own file), so it is opened in place.
  bool Open(std::string* damage) {
    if (!detail::OpenIndexed(path_, &bag_, damage)) return false;
    try {
      const detail::TopicTypes topics = ListTopics(bag_);
      detail::RequireTopic(path_, topics, options_.lidar_topic, detail::kCloudType);
      std::vector<std::string> wanted = {options_.lidar_topic};
      if (!options_.imu_topic.empty()) {
        detail::RequireTopic(path_, topics, options_.imu_topic, detail::kImuType);
        wanted.push_back(options_.imu_topic);
      }
      CheckFirstScan();
      view_ = std::make_unique<rosbag::View>(bag_, rosbag::TopicQuery(wanted));
      it_ = view_->begin();
    } catch (const rosbag::BagException& e) {
      throw std::runtime_error("bag '" + path_ + "': corrupt or truncated (" + e.what() + ")");
    }
    return true;
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
        throw std::runtime_error("bag '" + path_ + "', topic '" + detail::Printable(topic) +
                                 "', message " + std::to_string(message_index_) + ": " + e.what());
      }
      if (delivered) return true;
    }
    return false;
  }

  const LogReadCounters& counters() const override { return counters_; }
  PointTimeConvention time_convention() const override { return convention_; }

 private:
  void CheckFirstScan() {
    rosbag::View scans(bag_, rosbag::TopicQuery(options_.lidar_topic));
    if (scans.begin() == scans.end()) {
      if (convention_ == PointTimeConvention::kAuto) convention_ = PointTimeConvention::kNone;
      return;
    }
    if (!scans.begin()->isType<sensor_msgs::PointCloud2>()) {
      throw std::runtime_error("bag '" + path_ + "': unreadable PointCloud2");
    }
    convention_ =
        detail::CheckFirstScan(detail::ReadMessage<sensor_msgs::PointCloud2>(*scans.begin()),
                               convention_, path_, options_.lidar_topic);
  }

  bool ReadScan(const rosbag::MessageInstance& m, LogMessage* message) {
    if (!m.isType<sensor_msgs::PointCloud2>()) {
      throw std::runtime_error("unreadable PointCloud2 on " + m.getTopic());
    }
    detail::DecodeScan(detail::ReadMessage<sensor_msgs::PointCloud2>(m), convention_, message,
                       &counters_);
    return true;
  }

  bool ReadImu(const rosbag::MessageInstance& m, LogMessage* message) {
    if (!m.isType<sensor_msgs::Imu>()) {
      throw std::runtime_error("unreadable Imu on " + m.getTopic());
    }
    return detail::DecodeImu(detail::ReadMessage<sensor_msgs::Imu>(m), options_.imu_accel_scale,
                             message, &counters_);
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
  auto reader = std::make_unique<BagReader>(path, options);
  std::string damage;
  if (reader->Open(&damage)) return reader;
  return detail::OpenRecoveredBag(path, options, damage);
}

}  // namespace hylo::logs
