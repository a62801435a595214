#pragma once
// A simulated session streamed into a log (a ROS1 bag or a ROS 2 recording) as a driver would
// have recorded it (its topics, its per-point time layout, its acceleration units), the truth
// kept for a TUM file.

#include <memory>
#include <string>
#include <vector>

#include "hylo/logs/log_writer.h"
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
  FileSink(const std::string& log_path, const BagLayout& layout, logs::LogFormat format)
      : log_(logs::CreateLogWriter(log_path, format)), layout_(layout) {}
  void OnImu(const ImuSample& s) override {
    ImuSample published = s;
    published.accel_imu /= layout_.accel_units_mps2;
    log_->WriteImu(layout_.imu_topic, published, "imu");
  }
  void OnScan(const LidarScan& s) override {
    log_->WriteScan(layout_.points_topic, s, layout_.point_layout, "lidar");
  }
  void OnTruth(const TruthSample& t) override {
    io::StampedPose pose;
    pose.t_ns = t.t_ns;
    pose.position = t.T_map_imu.translation();
    pose.orientation = Eigen::Quaterniond(t.T_map_imu.linear()).normalized();
    truth_.push_back(pose);
  }
  void Close() { log_->Close(); }
  const std::vector<io::StampedPose>& truth() const { return truth_; }

 private:
  std::unique_ptr<logs::LogWriter> log_;
  BagLayout layout_;
  std::vector<io::StampedPose> truth_;
};

}  // namespace hylo::sim
