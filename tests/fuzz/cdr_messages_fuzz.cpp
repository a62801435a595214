// Fuzz target: a ROS 2 message's CDR bytes as a rosbag2 or MCAP file holds them -> the plain
// types (cdr_messages.h), then a scan through DecodePointCloud2. The first byte picks the type:
// sensor_msgs/msg/PointCloud2, sensor_msgs/msg/Imu or livox_ros_driver2/msg/CustomMsg. A reader
// must refuse bytes that do not hold the message with CdrError (the rosbag2 reader adds the
// file, topic and message number), never read past them or allocate what a count announces.

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "cdr_messages.h"
#include "cdr_reader.h"
#include "fuzz_support.h"
#include "hylo/logs/pointcloud2.h"

namespace {

using hylo::fuzz::Require;
namespace logs = hylo::logs;
namespace detail = hylo::logs::detail;

void CheckCloud(const logs::PointCloud2Message& cloud, std::size_t size) {
  // Whatever the message announces, it holds no more bytes than it came in (Livox: 26 for 19).
  Require(cloud.data.size() <= 2 * size, "a cloud larger than its message");
  try {
    std::size_t dropped = 0;
    const hylo::LidarScan scan =
        logs::DecodePointCloud2(cloud, logs::PointTimeConvention::kAuto, &dropped);
    Require(scan.points.size() + dropped == uint64_t{cloud.width} * cloud.height,
            "decoded + dropped points differ from width * height");
    Require(scan.t_ns <= scan.end_t_ns, "scan ends before it starts");
  } catch (const std::runtime_error& e) {
    hylo::fuzz::RequireClearError(e, "");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const uint8_t* bytes = data + 1;
  const std::size_t n = size - 1;
  try {
    switch (data[0] % 3) {
      case 0:
        CheckCloud(detail::DecodeCdrPointCloud2(bytes, n), n);
        break;
      case 1:
        detail::DecodeCdrImu(bytes, n);
        break;
      default:
        CheckCloud(detail::DecodeCdrLivoxCustom(bytes, n), n);
        break;
    }
  } catch (const detail::CdrError& e) {
    hylo::fuzz::RequireClearError(e, "");
  }
  return 0;
}
