#pragma once
// The one place where ROS message types become hylo's and back: stamps, IMU samples, the
// PointCloud2 mirror that logs::DecodePointCloud2 reads, and messages from their serialized
// bytes. Shared by the bag reader and writer (hylo_io), the ROS node and the fuzz targets; it
// includes ROS headers, so it is given to those targets only and never installed (hylo's
// public headers never see ROS).

#include <ros/serialization.h>
#include <ros/time.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/logs/pointcloud2.h"

namespace hylo::logs::ros_bridge {

/// ros::serialization's input stream, with one more check: ROS resizes a vector to the
/// length its prefix announces before it reads the elements, so a corrupt prefix in a
/// few-byte message asks for up to 4 G elements. Every element takes at least one byte
/// (sizeof(T) for plain types), so a prefix announcing more than the bytes left is refused
/// before anything is allocated.
class BoundedIStream : public ros::serialization::IStream {
 public:
  BoundedIStream(uint8_t* data, uint32_t count) : IStream(data, count) {}

  template <typename T>
  void next(T& value) {
    ros::serialization::deserialize(*this, value);
  }

  template <typename T, typename Allocator>
  void next(std::vector<T, Allocator>& values) {
    uint32_t length = 0;
    if (getLength() >= sizeof(length)) std::memcpy(&length, getData(), sizeof(length));
    const uint64_t min_bytes = ros::message_traits::isSimple<T>() ? sizeof(T) : 1;
    if (uint64_t{length} * min_bytes > getLength()) {
      throw ros::serialization::StreamOverrunException(
          "an array announces " + std::to_string(length) + " elements, the message has " +
          std::to_string(getLength()) + " bytes left");
    }
    ros::serialization::deserialize(*this, values);
  }
};

/// A message from its serialized bytes (what a bag record holds). Throws
/// ros::serialization::StreamOverrunException (a std::runtime_error) when the bytes end early
/// or an array announces more elements than bytes remain.
template <class Message>
Message Deserialize(const uint8_t* bytes, std::size_t size) {
  if (size > std::numeric_limits<uint32_t>::max()) {
    throw ros::serialization::StreamOverrunException("message larger than 4 GiB");
  }
  Message message;
  // IStream takes a mutable pointer but only reads through it.
  BoundedIStream stream(const_cast<uint8_t*>(bytes), static_cast<uint32_t>(size));
  ros::serialization::deserialize(stream, message);
  return message;
}

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

/// An IMU sample: header.stamp -> t_ns, linear_acceleration * accel_scale -> accel_imu (some
/// drivers report g), angular_velocity -> gyro_imu. Values are passed on as they are (NaN
/// included): the caller decides what a non-finite sample means.
inline ImuSample FromRos(const sensor_msgs::Imu& msg, double accel_scale) {
  ImuSample imu;
  imu.t_ns = FromRosTime(msg.header.stamp);
  imu.accel_imu =
      accel_scale * Eigen::Vector3d(msg.linear_acceleration.x, msg.linear_acceleration.y,
                                    msg.linear_acceleration.z);
  imu.gyro_imu = {msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z};
  return imu;
}

/// The message of an IMU sample (accelerations as they are, m/s²), without an orientation
/// estimate (orientation_covariance[0] = -1, as sensor_msgs/Imu defines).
inline sensor_msgs::Imu ToRos(const ImuSample& imu, const std::string& frame_id) {
  sensor_msgs::Imu msg;
  msg.header.stamp = ToRosTime(imu.t_ns);
  msg.header.frame_id = frame_id;
  msg.orientation_covariance[0] = -1.0;
  msg.linear_acceleration.x = imu.accel_imu.x();
  msg.linear_acceleration.y = imu.accel_imu.y();
  msg.linear_acceleration.z = imu.accel_imu.z();
  msg.angular_velocity.x = imu.gyro_imu.x();
  msg.angular_velocity.y = imu.gyro_imu.y();
  msg.angular_velocity.z = imu.gyro_imu.z();
  return msg;
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

}  // namespace hylo::logs::ros_bridge
