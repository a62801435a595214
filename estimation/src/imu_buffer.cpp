#include "hylo/estimation/imu_buffer.h"

#include <algorithm>

namespace hylo::estimation {

void ImuBuffer::Add(const ImuSample& sample) {
  if (!enabled_) return;
  if (!samples_.empty() && sample.t_ns <= samples_.back().t_ns) return;
  samples_.push_back(sample);
}

void ImuBuffer::DropBefore(int64_t t_ns) {
  auto first_after = std::upper_bound(samples_.begin(), samples_.end(), t_ns,
                                      [](int64_t t, const ImuSample& s) { return t < s.t_ns; });
  if (first_after != samples_.begin()) samples_.erase(samples_.begin(), first_after - 1);
}

}  // namespace hylo::estimation
