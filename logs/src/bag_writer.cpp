#include "hylo/logs/bag_writer.h"

#include <rosbag/bag.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>

#include <algorithm>
#include <stdexcept>

#include "hylo/logs/ros_bridge.h"

namespace hylo::logs {

struct BagWriter::Impl {
  std::string path;
  rosbag::Bag bag;
  bool open = false;

  /// rosbag rejects receive times below ros::TIME_MIN (1 ns).
  template <typename Msg>
  void Write(const std::string& topic, int64_t receive_t_ns, const Msg& msg) {
    if (!open) throw std::logic_error("bag '" + path + "': write after Close()");
    try {
      bag.write(topic, ros_bridge::ToRosTime(std::max<int64_t>(receive_t_ns, 1)), msg);
    } catch (const rosbag::BagException& e) {
      throw std::runtime_error("bag '" + path + "': cannot write to " + topic + " (" + e.what() +
                               ")");
    }
  }
};

BagWriter::BagWriter(const std::string& path, BagCompression compression)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  try {
    impl_->bag.open(path, rosbag::bagmode::Write);
    impl_->bag.setCompression(compression == BagCompression::kBz2 ? rosbag::compression::BZ2
                              : compression == BagCompression::kLz4
                                  ? rosbag::compression::LZ4
                                  : rosbag::compression::Uncompressed);
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("bag '" + path + "': cannot be created (" + e.what() + ")");
  }
  impl_->open = true;
}

BagWriter::~BagWriter() {
  try {
    Close();
  } catch (...) {  // a destructor must not throw; call Close() to see the error
  }
}

void BagWriter::WriteImu(const std::string& topic, const ImuSample& imu,
                         const std::string& frame_id, int64_t receive_t_ns) {
  impl_->Write(topic, receive_t_ns >= 0 ? receive_t_ns : imu.t_ns,
               ros_bridge::ToRos(imu, frame_id));
}

void BagWriter::WriteScan(const std::string& topic, const LidarScan& scan,
                          PointTimeConvention layout, const std::string& frame_id) {
  PointCloud2Message cloud = EncodePointCloud2(scan, layout);
  cloud.frame_id = frame_id;
  impl_->Write(topic, scan.end_t_ns, ros_bridge::ToRos(std::move(cloud)));
}

void BagWriter::WriteCloud(const std::string& topic, const PointCloud2Message& cloud,
                           int64_t receive_t_ns) {
  impl_->Write(topic, receive_t_ns, ros_bridge::ToRos(PointCloud2Message(cloud)));
}

void BagWriter::Close() {
  if (!impl_->open) return;
  impl_->open = false;
  try {
    impl_->bag.close();
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("bag '" + impl_->path + "': cannot be closed (" + e.what() + ")");
  }
}

}  // namespace hylo::logs
