// Fuzz target: a sensor_msgs/PointCloud2 message as a bag record holds it (ROS serialization)
// -> LidarScan, through the bag reader's own steps (bounded deserialization, the plain mirror,
// DecodePointCloud2). The first byte picks the per-point time convention (auto, each driver's,
// none), so every layout's decoding runs on every input.

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz_support.h"
#include "hylo/logs/pointcloud2.h"
#include "hylo/logs/ros_bridge.h"

namespace {

using hylo::LidarScan;
using hylo::fuzz::Require;
using hylo::logs::PointTimeConvention;

constexpr PointTimeConvention kConventions[] = {
    PointTimeConvention::kAuto,  PointTimeConvention::kVelodyne,  PointTimeConvention::kOuster,
    PointTimeConvention::kHesai, PointTimeConvention::kRobosense, PointTimeConvention::kLivox,
    PointTimeConvention::kNone};

// What DecodePointCloud2 promises about a scan it returns.
void CheckScan(const hylo::logs::PointCloud2Message& cloud, const LidarScan& scan,
               std::size_t dropped) {
  Require(scan.points.size() + dropped == uint64_t{cloud.width} * cloud.height,
          "decoded + dropped points differ from width * height");
  Require(scan.t_ns <= scan.end_t_ns, "scan ends before it starts");
  for (const hylo::ScanPoint& p : scan.points) {
    Require(p.position_lidar.allFinite(), "a non-finite point was kept");
    Require(p.offset_ns >= 0 && p.offset_ns <= scan.end_t_ns - scan.t_ns,
            "a point's time offset lies outside [t_ns, end_t_ns]");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const PointTimeConvention convention = kConventions[data[0] % std::size(kConventions)];
  hylo::logs::PointCloud2Message cloud;
  try {
    cloud = hylo::logs::ros_bridge::FromRos(
        hylo::logs::ros_bridge::Deserialize<sensor_msgs::PointCloud2>(data + 1, size - 1));
  } catch (const ros::serialization::StreamOverrunException&) {
    return 0;  // the bag reader reports it as a corrupt message, naming the bag
  }
  try {
    std::size_t dropped = 0;
    const LidarScan scan = hylo::logs::DecodePointCloud2(cloud, convention, &dropped);
    CheckScan(cloud, scan, dropped);
  } catch (const std::runtime_error& e) {
    hylo::fuzz::RequireClearError(e, "");  // callers add the file name
  }
  return 0;
}
