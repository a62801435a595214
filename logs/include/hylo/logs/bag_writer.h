#pragma once
// ROS1 bag writing (rosbag_storage): IMU samples and scans in a real driver's PointCloud2
// layout, as the simulator and the tests produce them. ROS types stay out of this header.

#include <cstdint>
#include <memory>
#include <string>

#include "hylo/common/sensor_data.h"
#include "hylo/logs/log_reader.h"
#include "hylo/logs/log_writer.h"
#include "hylo/logs/pointcloud2.h"

namespace hylo::logs {

/// Writes a bag as a driver recording would look: each message's receive time is its stamp
/// (a scan's is its end time, when a driver publishes it), so readers get receive order.
/// rosbag refuses a receive time of 0: a message stamped 0 is filed at 1 ns (its header
/// keeps 0). Negative stamps throw std::invalid_argument. Not thread-safe.
/// How chunks are stored (rosbag's choices): none (what `rosbag record` writes by default),
/// bz2 or lz4.
enum class BagCompression { kNone, kBz2, kLz4 };

class BagWriter : public LogWriter {
 public:
  /// Creates (overwrites) `path`; throws std::runtime_error naming it if it cannot.
  explicit BagWriter(const std::string& path, BagCompression compression = BagCompression::kNone);
  ~BagWriter() override;  ///< closes the bag if Close() was not called (errors swallowed)
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  /// sensor_msgs/Imu: header.stamp = t_ns, linear_acceleration = accel_imu (m/s^2),
  /// angular_velocity = gyro_imu (rad/s), orientation unknown (orientation_covariance[0] = -1).
  /// Receive time = t_ns, or `receive_t_ns` when >= 0 (a late message, as tests need them).
  void WriteImu(const std::string& topic, const ImuSample& imu, const std::string& frame_id,
                int64_t receive_t_ns = -1) override;
  /// sensor_msgs/PointCloud2 in the field layout of `layout`'s driver (EncodePointCloud2);
  /// `frame_id` replaces scan.frame_id. Receive time = scan.end_t_ns.
  void WriteScan(const std::string& topic, const LidarScan& scan, PointTimeConvention layout,
                 const std::string& frame_id) override;
  /// Any cloud, as given (tests of odd layouts; converters). Receive time `receive_t_ns`.
  void WriteCloud(const std::string& topic, const PointCloud2Message& cloud,
                  int64_t receive_t_ns) override;
  /// Writes the index and closes the file; further writes throw std::logic_error.
  /// Throws std::runtime_error naming the file on an I/O error.
  void Close() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hylo::logs
