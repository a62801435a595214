// DescribeBag: topics, counts, rates, stamps and PointCloud2 layouts, read from the bag's
// index (only the first and last message of Imu/PointCloud2 topics are deserialized), or, for
// a bag whose index cannot be read, from every readable record.

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

#include "bag_decode.h"
#include "bag_open.h"
#include "hylo/logs/bag_reader.h"
#include "hylo/logs/ros_bridge.h"

namespace hylo::logs {
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

void DescribeFields(const sensor_msgs::PointCloud2& cloud, BagTopicDescription* topic) {
  for (const auto& f : cloud.fields) {
    topic->point_fields.push_back({f.name, f.datatype, f.offset, f.count});
  }
  topic->detected_convention = DetectPointTimeConvention(topic->point_fields);
}

void SetMeanRate(BagTopicDescription* topic) {
  const int64_t span_ns = topic->last_stamp_ns - topic->first_stamp_ns;
  if (topic->message_count > 1 && span_ns > 0) {
    topic->mean_rate_hz = static_cast<double>(topic->message_count - 1) / (span_ns * 1e-9);
  }
}

/// header.stamp read straight from the serialized bytes of an Imu or PointCloud2 (both start
/// with std_msgs/Header: seq u32, stamp u32 s + u32 ns); the receive time otherwise.
int64_t RecordStamp(const detail::BagMessageRecord& r, bool* from_header) {
  const std::string& type = r.connection->type;
  *from_header = (type == detail::kImuType || type == detail::kCloudType) && r.size >= 12;
  if (!*from_header) return r.receive_ns;
  const auto u32 = [&](int i) {
    return uint32_t{r.data[i]} | uint32_t{r.data[i + 1]} << 8 | uint32_t{r.data[i + 2]} << 16 |
           uint32_t{r.data[i + 3]} << 24;
  };
  return int64_t{u32(4)} * 1000000000 + int64_t{u32(8)};
}

/// Every complete record of a bag whose index cannot be read.
BagDescription DescribeRecoveredBag(const std::string& path, const std::string& damage) {
  detail::BagRecordScanner scanner(path);
  BagDescription d;
  d.path = path;
  d.file_size_bytes = scanner.file_bytes();
  LogRecovery r;
  r.damage = damage;
  r.file_bytes = scanner.file_bytes();
  std::map<std::string, BagTopicDescription> topics;  // sorted by topic name
  std::map<std::string, bool> all_from_header;
  detail::BagMessageRecord record;
  while (scanner.Next(&record)) {
    if (r.messages++ == 0) r.first_receive_ns = record.receive_ns;
    r.last_receive_ns = record.receive_ns;
    BagTopicDescription& t = topics[record.connection->topic];
    bool from_header = false;
    const int64_t stamp = RecordStamp(record, &from_header);
    if (t.message_count++ == 0) {
      t.first_stamp_ns = stamp;
      all_from_header[record.connection->topic] = true;
      if (record.connection->type == detail::kCloudType) {
        try {
          DescribeFields(detail::Deserialize<sensor_msgs::PointCloud2>(record), &t);
        } catch (const ros::Exception&) {  // an unreadable first cloud: no field list
        }
      }
    }
    t.last_stamp_ns = stamp;
    all_from_header[record.connection->topic] &= from_header;
  }
  for (const auto& [id, c] : scanner.connections()) {
    BagTopicDescription& t = topics[c.topic];
    t.name = c.topic;
    t.type = c.type;
    t.stamps_from_header = t.message_count > 0 && all_from_header[c.topic];
    SetMeanRate(&t);
  }
  for (auto& [name, t] : topics) d.topics.push_back(std::move(t));
  d.message_count = r.messages;
  d.start_ns = r.first_receive_ns;
  d.end_ns = r.last_receive_ns;
  d.duration_s = r.messages > 0 ? r.span_s() : 0.0;
  r.stop_reason = scanner.stop_reason();
  r.unreadable_bytes = scanner.file_bytes() - scanner.readable_bytes();
  d.recovery = r;
  return d;
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
  SetMeanRate(&topic);
  if (type == detail::kCloudType) {
    if (first->isType<sensor_msgs::PointCloud2>()) {
      DescribeFields(detail::ReadMessage<sensor_msgs::PointCloud2>(*first), &topic);
    }
  }
  return topic;
}

}  // namespace

BagDescription DescribeBag(const std::string& path) {
  rosbag::Bag bag;
  std::string damage;
  if (!detail::OpenIndexed(path, &bag, &damage)) return DescribeRecoveredBag(path, damage);
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

}  // namespace hylo::logs
