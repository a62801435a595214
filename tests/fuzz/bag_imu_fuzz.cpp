// Fuzz target: a sensor_msgs/Imu message as a bag record holds it (ROS serialization) ->
// ImuSample, through the bag reader's own steps (bounded deserialization, ros_bridge::FromRos).

#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "hylo/io/ros_bridge.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  sensor_msgs::Imu msg;
  try {
    msg = hylo::io::ros_bridge::Deserialize<sensor_msgs::Imu>(data, size);
  } catch (const ros::serialization::StreamOverrunException&) {
    return 0;  // the bag reader reports it as a corrupt message, naming the bag
  }
  for (const double accel_scale : {1.0, 9.80665}) {
    const hylo::ImuSample imu = hylo::io::ros_bridge::FromRos(msg, accel_scale);
    hylo::fuzz::Require(imu.t_ns >= 0, "a ROS stamp (unsigned seconds) became negative");
    hylo::fuzz::Require(
        imu.gyro_imu.x() == msg.angular_velocity.x || (imu.gyro_imu.x() != imu.gyro_imu.x()),
        "the gyro value changed on the way");
  }
  return 0;
}
