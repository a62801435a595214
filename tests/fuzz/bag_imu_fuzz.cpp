// Fuzz target: a sensor_msgs/Imu message as a bag record holds it (ROS serialization) ->
// ImuSample, through the bag reader's own steps (bounded deserialization, ros_bridge::FromRos).

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "hylo/logs/ros_bridge.h"

namespace {

// The same value, or both NaN (a NaN sample is passed on for the reader to count and drop).
bool Same(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  sensor_msgs::Imu msg;
  try {
    msg = hylo::logs::ros_bridge::Deserialize<sensor_msgs::Imu>(data, size);
  } catch (const ros::serialization::StreamOverrunException&) {
    return 0;  // the bag reader reports it as a corrupt message, naming the bag
  }
  const double g = 9.80665;  // a driver that reports g (Livox)
  const hylo::ImuSample imu = hylo::logs::ros_bridge::FromRos(msg, g);
  // ROS stamps are unsigned seconds + nanoseconds: always a non-negative int64 of ns.
  hylo::fuzz::Require(imu.t_ns >= 0 && imu.t_ns == int64_t{msg.header.stamp.sec} * 1000000000 +
                                                       msg.header.stamp.nsec,
                      "the stamp changed on the way");
  hylo::fuzz::Require(Same(imu.accel_imu.z(), g * msg.linear_acceleration.z) &&
                          Same(imu.gyro_imu.x(), msg.angular_velocity.x),
                      "a value changed on the way");
  return 0;
}
