#pragma once
// A simulated session streamed into a ROS1 bag as a driver would have recorded it (its
// topics, its per-point time layout, its acceleration units), the truth kept for a TUM file.

#include <string>
#include <vector>

#include "hylo/logs/bag_writer.h"
#include "hylo/io/trajectory_io.h"
#include "hylo/sim/simulator.h"

namespace hylo::sim {

/// How the bag looks: topics, the lidar driver's field layout, and what the IMU driver's
/// accelerations are divided by (1: m/s^2; ~9.81 for drivers that publish g).
struct BagLayout {
  std::string imu_topic = "/imu";
  std::string points_topic = "/points";
  logs::PointTimeConvention point_layout = logs::PointTimeConvention::kVelodyne;
  double accel_units_mps2 = 1.0;
};

class FileSink : public SessionSink {
 public:
  FileSink(const std::string& bag_path, const BagLayout& layout)
      : bag_(bag_path), layout_(layout) {}
  void OnImu(const ImuSample& s) override {
    ImuSample published = s;
    published.accel_imu /= layout_.accel_units_mps2;
    bag_.WriteImu(layout_.imu_topic, published, "imu");
  }
  void OnScan(const LidarScan& s) override {
    bag_.WriteScan(layout_.points_topic, s, layout_.point_layout, "lidar");
  }
  void OnTruth(const TruthSample& t) override {
    io::StampedPose pose;
    pose.t_ns = t.t_ns;
    pose.position = t.T_map_imu.translation();
    pose.orientation = Eigen::Quaterniond(t.T_map_imu.linear()).normalized();
    truth_.push_back(pose);
  }
  void Close() { bag_.Close(); }
  const std::vector<io::StampedPose>& truth() const { return truth_; }

 private:
  logs::BagWriter bag_;
  BagLayout layout_;
  std::vector<io::StampedPose> truth_;
};

}  // namespace hylo::sim
