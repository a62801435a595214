#pragma once
// The hand-over between ROS callbacks (which decode messages) and the worker thread (which
// runs the odometry pipeline). Bounded, so memory stays flat when the worker falls behind or
// one stream stalls: the oldest waiting scan is dropped first (the IMU keeps propagating
// across a missing scan), IMU samples only beyond a much larger bound. With an IMU, a scan is
// released only once the IMU has passed its end, and IMU samples only up to the first one
// after the released scans: whatever waits for the other stream waits here, bounded, and not
// in the pipeline's (unbounded) measurement queue. A message whose stamp does not come after
// the previous one on its stream (late, duplicated or out of order) is dropped and counted,
// never fatal. No ROS type here: unit-tested without a master.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"

namespace hylo::rosnode {

struct InputQueueOptions {
  std::size_t max_scans = 5;     ///< scans waiting for the worker; beyond, the oldest is
                                 ///< dropped, >= 1
  std::size_t max_imu = 4000;    ///< IMU samples waiting (20 s at 200 Hz); beyond, the oldest
                                 ///< is dropped, >= 1
  bool wait_for_imu = true;      ///< release scans as the IMU covers them (see above); false
                                 ///< without an IMU: everything is released at once
  bool IsValid(std::string* why) const;
};

struct InputCounters {
  std::size_t scans_received = 0;
  std::size_t imu_received = 0;
  std::size_t scans_out_of_order = 0;  ///< start stamp not after the previous scan's: dropped
  std::size_t imu_out_of_order = 0;    ///< stamp not after the previous sample's: dropped
  std::size_t scans_dropped_full = 0;  ///< oldest scan dropped because the queue was full
  std::size_t imu_dropped_full = 0;    ///< oldest sample dropped because the queue was full
  std::size_t max_scans_waiting = 0;   ///< high-water mark
  std::size_t max_imu_waiting = 0;     ///< high-water mark
};

class InputQueue {
 public:
  /// Throws std::invalid_argument naming the field when `options` is not valid.
  explicit InputQueue(const InputQueueOptions& options);

  /// False when the scan was dropped as late / out of order.
  bool PushScan(LidarScan scan);
  /// False when the sample was dropped as late / out of order.
  bool PushImu(const ImuSample& sample);

  /// Waits up to `timeout` for a releasable scan, then moves what can be released (in
  /// arrival order per stream) into `imu` and `scans` (appended). After Close() everything is
  /// released; false once closed and nothing is left.
  bool Pop(std::vector<ImuSample>* imu, std::vector<LidarScan>* scans,
           std::chrono::milliseconds timeout);
  /// Wakes the worker; later pushes are ignored.
  void Close();
  /// Wakes a waiting Pop without data (e.g. a service request is pending).
  void Notify();

  InputCounters counters() const;

 private:
  /// With wait_for_imu, the IMU has reached the scan's end (the pipeline can process it).
  bool ScanReady(const LidarScan& scan) const;

  InputQueueOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<LidarScan> scans_;
  std::deque<ImuSample> imu_;
  int64_t last_scan_t_ns_ = INT64_MIN;
  int64_t last_imu_t_ns_ = INT64_MIN;
  int64_t released_scan_end_ns_ = INT64_MIN;  ///< latest end of a released scan
  int64_t released_imu_t_ns_ = INT64_MIN;     ///< stamp of the last released IMU sample
  bool closed_ = false;
  bool notified_ = false;
  InputCounters counters_;
};

}  // namespace hylo::rosnode
