#include "bag_decode.h"

#include "hylo/logs/ros_bridge.h"

namespace hylo::logs::detail {

PointTimeConvention CheckFirstScan(sensor_msgs::PointCloud2 first, PointTimeConvention convention,
                                   const std::string& path, const std::string& topic) {
  return CheckFirstCloud(ros_bridge::FromRos(std::move(first)), convention, path, topic);
}

void DecodeScan(sensor_msgs::PointCloud2&& msg, PointTimeConvention convention, LogMessage* message,
                LogReadCounters* counters) {
  DecodeScan(ros_bridge::FromRos(std::move(msg)), convention, message, counters);
}

bool DecodeImu(const sensor_msgs::Imu& msg, double accel_scale, LogMessage* message,
               LogReadCounters* counters) {
  // Some drivers (Livox) publish g instead of m/s^2; the configuration says which.
  return AcceptImu(ros_bridge::FromRos(msg, accel_scale), message, counters);
}

}  // namespace hylo::logs::detail
