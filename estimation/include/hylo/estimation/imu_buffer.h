#pragma once
// The raw IMU samples a back-end holds between its last update and the newest sample: what
// both the filter's propagation and the smoother's preintegration read, and what PredictAt
// (hence undistortion) integrates. It also follows how much the signal has been varying, which
// is how far a measurement interpolated across a gap in the stream can be trusted.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/estimation/imu_propagation.h"

namespace hylo::estimation {

class ImuBuffer {
 public:
  /// `enabled` false (no IMU): every sample is ignored. Consecutive samples farther apart than
  /// `gap_ns` bound a gap.
  ImuBuffer(bool enabled, int64_t gap_ns) : enabled_(enabled), gap_ns_(gap_ns) {}

  /// Appends `sample`; samples not newer than the last one are ignored (the measurement queue
  /// sorts the streams, so this only guards the back-end's own invariant).
  void Add(const ImuSample& sample);
  /// Drops the samples before `t_ns`, keeping the last one at or before it: the next interval
  /// is interpolated from it.
  void DropBefore(int64_t t_ns);

  /// The gap model of the signal over the last seconds (spread and mean, ImuGapModel).
  ImuGapModel GapModel() const;
  /// MakeIntervals over the buffered samples with GapModel(): intervals inside a gap carry the
  /// spread, times after the last sample read the mean.
  std::vector<ImuInterval> Intervals(int64_t t0_ns, int64_t t1_ns) const;

  const std::vector<ImuSample>& samples() const { return samples_; }
  bool empty() const { return samples_.empty(); }

 private:
  /// Exponentially weighted mean and variance of a vector signal (West 1979, weighted
  /// incremental form); the variance is the mean over the three axes.
  struct Spread {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    double variance = 0.0;
    bool started = false;
    void Add(const Eigen::Vector3d& x, double weight);
  };

  bool enabled_;
  int64_t gap_ns_;
  std::vector<ImuSample> samples_;  // time order
  Spread accel_, gyro_;             // over samples not separated by a gap
};

}  // namespace hylo::estimation
