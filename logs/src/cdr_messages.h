#pragma once
// Private to hylo_logs: the ROS 2 messages hylo reads and writes, in CDR (cdr_reader.h):
// sensor_msgs/msg/PointCloud2 and sensor_msgs/msg/Imu both ways, livox_ros_driver2/msg/CustomMsg
// read, and their message definitions (the ros2msg text a rosbag2 MCAP file carries as schema).
// Decoding yields the same plain types as the ROS1 path (PointCloud2Message, ImuSample), so that
// layouts, per-point time conventions and drops are handled once (message_decode.h).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/logs/pointcloud2.h"

namespace hylo::logs::detail {

constexpr char kRos2CloudType[] = "sensor_msgs/msg/PointCloud2";
constexpr char kRos2ImuType[] = "sensor_msgs/msg/Imu";
constexpr char kLivoxCustomType[] = "livox_ros_driver2/msg/CustomMsg";

/// sensor_msgs/msg/PointCloud2. Throws CdrError on bytes that do not hold one.
PointCloud2Message DecodeCdrPointCloud2(const uint8_t* data, std::size_t size);

/// sensor_msgs/msg/Imu: header.stamp -> t_ns, linear_acceleration (as stored) -> accel_imu,
/// angular_velocity -> gyro_imu; NaN passed on. Throws CdrError.
ImuSample DecodeCdrImu(const uint8_t* data, std::size_t size);

/// livox_ros_driver2/msg/CustomMsg as the PointCloud2 the same driver publishes in its
/// PointCloud2 mode (xfer_format 0; the Livox layout of pointcloud2.h): x y z, reflectivity as
/// intensity, tag, line, and timestamp = timebase + offset_time in absolute ns; header.stamp
/// kept. Throws CdrError.
PointCloud2Message DecodeCdrLivoxCustom(const uint8_t* data, std::size_t size);

/// A point cloud of `type` (kRos2CloudType, or kLivoxCustomType as above).
PointCloud2Message DecodeCdrCloud(const std::string& type, const uint8_t* data, std::size_t size);

std::vector<uint8_t> EncodeCdrPointCloud2(const PointCloud2Message& cloud);
/// Without an orientation estimate (orientation_covariance[0] = -1, as sensor_msgs defines).
std::vector<uint8_t> EncodeCdrImu(const ImuSample& imu, const std::string& frame_id);

/// One Livox point of a CustomMsg (for writers of test data).
struct LivoxCustomPoint {
  uint32_t offset_time_ns = 0;
  float x = 0, y = 0, z = 0;
  uint8_t reflectivity = 0, tag = 0, line = 0;
};
std::vector<uint8_t> EncodeCdrLivoxCustom(int64_t stamp_ns, const std::string& frame_id,
                                          uint64_t timebase_ns,
                                          const std::vector<LivoxCustomPoint>& points);

/// The ros2msg definition of kRos2CloudType, kRos2ImuType or kLivoxCustomType with the types
/// it uses appended (each after a line of 80 '=' and "MSG: <package>/<name>"), as rosbag2 stores
/// it in MCAP schemas; "" for other types.
std::string Ros2MessageDefinition(const std::string& type);

}  // namespace hylo::logs::detail
