#include "bag_decode.h"

#include <stdexcept>

#include "hylo/logs/ros_bridge.h"
#include "printable.h"

namespace hylo::logs::detail {
namespace {

std::string Describe(const TopicTypes& topics) {
  std::string out;
  for (const auto& [topic, types] : topics) {
    out += (out.empty() ? "" : ", ") + Printable(topic) + " (" + Printable(types.front()) + ")";
  }
  return out.empty() ? "none" : out;
}

}  // namespace

void RequireTopic(const std::string& path, const TopicTypes& topics, const std::string& topic,
                  const std::string& type) {
  const auto it = topics.find(topic);
  if (it == topics.end()) {
    throw std::runtime_error("bag '" + path + "': no topic '" + topic + "' (" + type +
                             "); topics in the bag: " + Describe(topics));
  }
  for (const std::string& found : it->second) {
    if (found != type) {
      throw std::runtime_error("bag '" + path + "': topic '" + topic + "' has type " +
                               Printable(found) + ", expected " + type);
    }
  }
}

PointTimeConvention CheckFirstScan(sensor_msgs::PointCloud2 first, PointTimeConvention convention,
                                   const std::string& path, const std::string& topic) {
  PointCloud2Message cloud = ros_bridge::FromRos(std::move(first));
  if (convention == PointTimeConvention::kAuto) {
    convention = DetectPointTimeConvention(cloud.fields);
  }
  try {
    DecodePointCloud2(cloud, convention, nullptr);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("bag '" + path + "', topic '" + topic +
                             "', first message: " + e.what());
  }
  return convention;
}

void DecodeScan(sensor_msgs::PointCloud2&& msg, PointTimeConvention convention, LogMessage* message,
                LogReadCounters* counters) {
  message->kind = LogMessage::Kind::kScan;
  message->scan = DecodePointCloud2(ros_bridge::FromRos(std::move(msg)), convention,
                                    &counters->dropped_non_finite_points);
  ++counters->scan_messages;
  if (message->scan.points.empty()) ++counters->empty_scans;
}

bool DecodeImu(const sensor_msgs::Imu& msg, double accel_scale, LogMessage* message,
               LogReadCounters* counters) {
  // Some drivers (Livox) publish g instead of m/s^2; the configuration says which.
  message->imu = ros_bridge::FromRos(msg, accel_scale);
  const ImuSample& imu = message->imu;
  if (!imu.accel_imu.allFinite() || !imu.gyro_imu.allFinite()) {
    ++counters->dropped_non_finite_imu;
    return false;
  }
  message->kind = LogMessage::Kind::kImu;
  ++counters->imu_messages;
  return true;
}

}  // namespace hylo::logs::detail
