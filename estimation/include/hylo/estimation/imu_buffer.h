#pragma once
// The raw IMU samples a back-end holds between its last update and the newest sample: what
// both the filter's propagation and the smoother's preintegration read, and what PredictAt
// (hence undistortion) integrates.

#include <cstdint>
#include <vector>

#include "hylo/common/sensor_data.h"

namespace hylo::estimation {

class ImuBuffer {
 public:
  /// `enabled` false (no IMU): every sample is ignored.
  explicit ImuBuffer(bool enabled) : enabled_(enabled) {}

  /// Appends `sample`; samples not newer than the last one are ignored (the measurement queue
  /// sorts the streams, so this only guards the back-end's own invariant).
  void Add(const ImuSample& sample);
  /// Drops the samples before `t_ns`, keeping the last one at or before it: the next interval
  /// is interpolated from it.
  void DropBefore(int64_t t_ns);

  const std::vector<ImuSample>& samples() const { return samples_; }
  bool empty() const { return samples_.empty(); }

 private:
  bool enabled_;
  std::vector<ImuSample> samples_;  // time order
};

}  // namespace hylo::estimation
