#include "hylo/estimation/imu_buffer.h"

#include <algorithm>
#include <cmath>

#include "hylo/common/time.h"

namespace hylo::estimation {
namespace {

// How far back the spread looks (time constant of its weights), s: a few of a ground
// vehicle's manoeuvres, yet short enough to follow it from driving to standing still.
constexpr double kSpreadTimeConstantS = 2.0;

}  // namespace

void ImuBuffer::Spread::Add(const Eigen::Vector3d& x, double weight) {
  if (!started) {
    mean = x;
    started = true;
    return;
  }
  const Eigen::Vector3d d = x - mean;
  mean += weight * d;
  variance = (1.0 - weight) * (variance + weight * d.squaredNorm() / 3.0);
}

void ImuBuffer::Add(const ImuSample& sample) {
  if (!enabled_) return;
  if (!samples_.empty()) {
    const int64_t dt_ns = sample.t_ns - samples_.back().t_ns;
    if (dt_ns <= 0) return;
    if (dt_ns <= gap_ns_) {
      const double w = std::min(1.0, NanosToSeconds(dt_ns) / kSpreadTimeConstantS);
      accel_.Add(sample.accel_imu, w);
      gyro_.Add(sample.gyro_imu, w);
    }
  }
  samples_.push_back(sample);
}

void ImuBuffer::DropBefore(int64_t t_ns) {
  auto first_after = std::upper_bound(samples_.begin(), samples_.end(), t_ns,
                                      [](int64_t t, const ImuSample& s) { return t < s.t_ns; });
  if (first_after != samples_.begin()) samples_.erase(samples_.begin(), first_after - 1);
}

ImuGapModel ImuBuffer::GapModel() const {
  ImuGapModel gap;
  gap.gap_ns = gap_ns_;
  gap.accel_sigma_mps2 = std::sqrt(accel_.variance);
  gap.gyro_sigma_radps = std::sqrt(gyro_.variance);
  // Before two close samples there is no mean yet: the last sample is the best guess.
  const bool have_mean = accel_.started || samples_.empty();
  gap.accel_mean_imu = have_mean ? accel_.mean : samples_.back().accel_imu;
  gap.gyro_mean_imu = have_mean ? gyro_.mean : samples_.back().gyro_imu;
  return gap;
}

std::vector<ImuInterval> ImuBuffer::Intervals(int64_t t0_ns, int64_t t1_ns) const {
  const ImuGapModel gap = GapModel();
  return MakeIntervals(samples_, t0_ns, t1_ns, &gap);
}

}  // namespace hylo::estimation
