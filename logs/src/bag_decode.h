#pragma once
// Private to hylo_logs: what both ROS1 bag readers (through the index, or record by record for
// a damaged bag) do with the messages: sensor_msgs types into the format-free decoding of
// message_decode.h, and ROS1 message definitions checked.

#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "bag_records.h"
#include "hylo/logs/log_reader.h"
#include "message_decode.h"
#include "hylo/logs/ros_bridge.h"
#include "printable.h"

namespace hylo::logs::detail {

constexpr char kImuType[] = "sensor_msgs/Imu";
constexpr char kCloudType[] = "sensor_msgs/PointCloud2";

/// RequireTopic with one type.
inline void RequireTopic(const std::string& path, const TopicTypes& topics,
                         const std::string& topic, const std::string& type) {
  RequireTopic(path, topics, topic, std::vector<std::string>{type});
}

/// CheckFirstCloud on a ROS message.
PointTimeConvention CheckFirstScan(sensor_msgs::PointCloud2 first, PointTimeConvention convention,
                                   const std::string& path, const std::string& topic);

/// A scan message (empty scans are delivered and counted).
void DecodeScan(sensor_msgs::PointCloud2&& msg, PointTimeConvention convention, LogMessage* message,
                LogReadCounters* counters);

/// An IMU message; false (skipped and counted) for NaN/inf values.
bool DecodeImu(const sensor_msgs::Imu& msg, double accel_scale, LogMessage* message,
               LogReadCounters* counters);

/// A message record's bytes as `Msg`, through ros_bridge's bounded stream; throws
/// ros::serialization::StreamOverrunException when they are too short or an array announces
/// more elements than bytes remain.
template <class Msg>
Msg Deserialize(const BagMessageRecord& record) {
  return ros_bridge::Deserialize<Msg>(record.data, record.size);
}

/// Throws when a connection's message definition is not the one hylo was built with.
template <class Msg>
void RequireDefinition(const BagConnection& c) {
  const std::string expected = ros::message_traits::md5sum<Msg>();
  if (c.md5sum != expected && c.md5sum != "*") {
    throw std::runtime_error("topic '" + Printable(c.topic) + "' has " + Printable(c.type) +
                             " with md5sum " + Printable(c.md5sum) + ", expected " + expected);
  }
}

}  // namespace hylo::logs::detail
