#pragma once
// The one place where ROS message types become hylo's and back: stamps and the PointCloud2
// mirror that io::DecodePointCloud2 reads. Shared by the bag reader and writer (hylo_io) and
// the ROS node; it includes ROS headers, so it is given to those two targets only and never
// installed (hylo's public headers never see ROS).

#include <ros/time.h>
#include <sensor_msgs/PointCloud2.h>

#include <stdexcept>
#include <string>
#include <utility>

#include "hylo/io/pointcloud2.h"

namespace hylo::io::ros_bridge {

inline int64_t FromRosTime(const ros::Time& t) {
  return static_cast<int64_t>(t.sec) * 1000000000 + static_cast<int64_t>(t.nsec);
}

/// ros::Time holds unsigned seconds: negative stamps cannot be written.
inline ros::Time ToRosTime(int64_t t_ns) {
  if (t_ns < 0) throw std::invalid_argument("negative stamp " + std::to_string(t_ns) + " ns");
  ros::Time t;
  t.fromNSec(static_cast<uint64_t>(t_ns));
  return t;
}

/// The message's bytes in the plain mirror (moved: pass an rvalue to avoid copying the points).
inline PointCloud2Message FromRos(sensor_msgs::PointCloud2 msg) {
  PointCloud2Message cloud;
  cloud.stamp_ns = FromRosTime(msg.header.stamp);
  cloud.frame_id = std::move(msg.header.frame_id);
  cloud.height = msg.height;
  cloud.width = msg.width;
  cloud.fields.reserve(msg.fields.size());
  for (const auto& f : msg.fields) cloud.fields.push_back({f.name, f.datatype, f.offset, f.count});
  cloud.is_bigendian = msg.is_bigendian != 0;
  cloud.point_step = msg.point_step;
  cloud.row_step = msg.row_step;
  cloud.data = std::move(msg.data);
  cloud.is_dense = msg.is_dense != 0;
  return cloud;
}

inline sensor_msgs::PointCloud2 ToRos(PointCloud2Message&& cloud) {
  sensor_msgs::PointCloud2 msg;
  msg.header.stamp = ToRosTime(cloud.stamp_ns);
  msg.header.frame_id = std::move(cloud.frame_id);
  msg.height = cloud.height;
  msg.width = cloud.width;
  for (const auto& f : cloud.fields) {
    sensor_msgs::PointField field;
    field.name = f.name;
    field.datatype = f.datatype;
    field.offset = f.offset;
    field.count = f.count;
    msg.fields.push_back(field);
  }
  msg.is_bigendian = cloud.is_bigendian;
  msg.point_step = cloud.point_step;
  msg.row_step = cloud.row_step;
  msg.data = std::move(cloud.data);
  msg.is_dense = cloud.is_dense;
  return msg;
}

}  // namespace hylo::io::ros_bridge
