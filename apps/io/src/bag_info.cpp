// DescribeBag: topics, counts, rates, stamps and PointCloud2 layouts, read from the bag's
// index; only the first and last message of Imu/PointCloud2 topics are deserialized.

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "bag_open.h"
#include "hylo/io/bag_reader.h"
#include "hylo/io/ros_bridge.h"

namespace hylo::io {
namespace {

/// The stamp of a message: header.stamp for the types hylo reads, else the receive time.
int64_t StampOf(const rosbag::MessageInstance& m, bool* from_header) {
  if (m.isType<sensor_msgs::Imu>()) {
    *from_header = true;
    return ros_bridge::FromRosTime(detail::ReadMessage<sensor_msgs::Imu>(m).header.stamp);
  }
  if (m.isType<sensor_msgs::PointCloud2>()) {
    *from_header = true;
    return ros_bridge::FromRosTime(detail::ReadMessage<sensor_msgs::PointCloud2>(m).header.stamp);
  }
  *from_header = false;
  return ros_bridge::FromRosTime(m.getTime());
}

void DescribeFields(const rosbag::MessageInstance& first, BagTopicDescription* topic) {
  if (!first.isType<sensor_msgs::PointCloud2>()) return;
  for (const auto& f : detail::ReadMessage<sensor_msgs::PointCloud2>(first).fields) {
    topic->point_fields.push_back({f.name, f.datatype, f.offset, f.count});
  }
  topic->detected_convention = DetectPointTimeConvention(topic->point_fields);
}

BagTopicDescription DescribeTopic(const rosbag::Bag& bag, const std::string& name,
                                  const std::string& type) {
  BagTopicDescription topic;
  topic.name = name;
  topic.type = type;
  rosbag::View view(bag, rosbag::TopicQuery(name));
  std::optional<rosbag::MessageInstance> first, last;
  for (const rosbag::MessageInstance& m : view) {  // index only: no message data is read
    if (!first) first.emplace(m);
    last.emplace(m);
    ++topic.message_count;
  }
  if (!first) return topic;
  bool first_from_header = false;
  bool last_from_header = false;
  topic.first_stamp_ns = StampOf(*first, &first_from_header);
  topic.last_stamp_ns = StampOf(*last, &last_from_header);
  topic.stamps_from_header = first_from_header && last_from_header;
  const int64_t span_ns = topic.last_stamp_ns - topic.first_stamp_ns;
  if (topic.message_count > 1 && span_ns > 0) {
    topic.mean_rate_hz = static_cast<double>(topic.message_count - 1) / (span_ns * 1e-9);
  }
  if (type == "sensor_msgs/PointCloud2") DescribeFields(*first, &topic);
  return topic;
}

}  // namespace

BagDescription DescribeBag(const std::string& path) {
  rosbag::Bag bag;
  detail::OpenForReading(path, &bag);
  BagDescription d;
  d.path = path;
  std::error_code ec;
  d.file_size_bytes = std::filesystem::file_size(path, ec);
  try {
    rosbag::View all(bag);
    d.message_count = all.size();
    if (d.message_count > 0) {
      d.start_ns = ros_bridge::FromRosTime(all.getBeginTime());
      d.end_ns = ros_bridge::FromRosTime(all.getEndTime());
      d.duration_s = (d.end_ns - d.start_ns) * 1e-9;
    }
    std::map<std::string, std::string> types;  // sorted by topic name
    for (const rosbag::ConnectionInfo* c : all.getConnections()) {
      types.emplace(c->topic, c->datatype);
    }
    for (const auto& [name, type] : types) d.topics.push_back(DescribeTopic(bag, name, type));
  } catch (const std::exception& e) {
    throw std::runtime_error("bag '" + path + "': corrupt or truncated (" + e.what() + ")");
  }
  return d;
}

}  // namespace hylo::io
