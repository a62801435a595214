#pragma once
// Orders the two sensor streams and hands out one scan at a time with the IMU samples that
// span it. Bad stamps are dropped one message at a time and counted: a single sample from
// the past never clears the buffers (a known failure of naive LIO front ends). IMU samples
// with NaN/inf or clipped (saturated) values are dropped and counted the same way: every
// estimator downstream sees only finite, in-range samples, and a run of dropped ones is a gap.

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"

namespace hylo::odometry {

struct MeasurementQueueOptions {
  bool use_imu = true;              ///< false: scans are released without waiting for IMU
  int64_t imu_gap_ns = 50'000'000;  ///< consecutive IMU stamps farther apart are a gap, ns
  /// How long scans wait for an IMU that has gone silent, ns: a dropout up to this long is
  /// bridged with the samples on both sides of it; past it the IMU is taken as stopped and the
  /// lidar carries the estimate on (rather than every scan being held until it comes back).
  int64_t max_imu_wait_ns = 1'000'000'000;
  double accel_range_mps2 = 0.0;  ///< |accel| >= this on any axis: clipped, dropped; 0 = off
  double gyro_range_radps = 0.0;  ///< |gyro| >= this on any axis: clipped, dropped; 0 = off
  bool IsValid(std::string* why) const;
};

/// What the queue dropped or noticed, over the whole run.
struct QueueCounters {
  std::size_t imu_duplicates = 0;   ///< same stamp as a buffered or the last handed-out sample
  std::size_t imu_stale = 0;        ///< older than what was already handed out
  std::size_t scan_duplicates = 0;  ///< same start stamp as a buffered scan
  std::size_t scan_stale = 0;       ///< started before the last handed-out scan
  std::size_t imu_non_finite = 0;   ///< NaN/inf values
  std::size_t imu_saturated = 0;    ///< a value at the sensor's full-scale range
  std::size_t imu_gaps = 0;         ///< intervals longer than imu_gap_ns
  int64_t longest_imu_gap_ns = 0;
  int64_t imu_gap_total_ns = 0;    ///< time covered by the gaps
  std::size_t scans_past_imu = 0;  ///< scans released while the IMU had stopped (see Pop)
};

/// One scan and the IMU samples up to (and including) the first one at or after its end that
/// were not handed out before.
struct MeasurementGroup {
  LidarScan scan;
  std::vector<ImuSample> imu;
};

class MeasurementQueue {
 public:
  explicit MeasurementQueue(const MeasurementQueueOptions& options);

  void AddImu(const ImuSample& sample);
  void AddScan(LidarScan scan);

  /// The next scan whose end is covered by IMU (any scan without IMU). A scan is also released
  /// without that cover when the IMU has stopped: a later scan started more than
  /// max_imu_wait_ns after the newest IMU sample. With `flush`, also IMU-less tails at the end
  /// of a log are released.
  bool Pop(MeasurementGroup* group, bool flush = false);

  /// IMU samples not yet handed out, with stamps <= t_ns, removed from the queue (used
  /// before the first scan, e.g. by the static initialisation).
  std::vector<ImuSample> PopImuUntil(int64_t t_ns);

  /// IMU samples not yet handed out, from the oldest on while each comes within
  /// `max_silence_ns` of the one before it (the first of `after_ns`) and has a stamp <= t_ns,
  /// removed from the queue: the stretch a state at `after_ns` can be carried through without
  /// crossing a silence of the IMU.
  std::vector<ImuSample> PopContinuousImu(int64_t after_ns, int64_t t_ns, int64_t max_silence_ns);

  const QueueCounters& counters() const { return counters_; }
  /// The newest IMU stamp received (INT64_MIN before any).
  int64_t newest_imu_ns() const { return newest_imu_ns_; }
  std::size_t pending_scans() const { return scans_.size(); }
  std::size_t pending_imu() const { return imu_.size(); }

 private:
  MeasurementQueueOptions options_;
  std::map<int64_t, ImuSample> imu_;      // by stamp: sorted, duplicates detectable
  std::map<int64_t, LidarScan> scans_;    // by start stamp
  int64_t last_imu_out_ns_ = INT64_MIN;   // newest IMU stamp handed out
  int64_t last_scan_out_ns_ = INT64_MIN;  // start stamp of the last handed-out scan
  int64_t newest_imu_ns_ = INT64_MIN;     // for gap detection in arrival order
  QueueCounters counters_;
};

}  // namespace hylo::odometry
