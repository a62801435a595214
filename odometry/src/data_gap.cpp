// Gaps in the data from the observed scan rate (data_gap.h).
#include "hylo/odometry/data_gap.h"

#include <algorithm>

#include "hylo/common/time.h"

namespace hylo::odometry {
namespace {

constexpr std::size_t kIntervalsKept = 15;
constexpr std::size_t kIntervalsNeeded = 5;

}  // namespace

int64_t ScanIntervalClock::UsualIntervalNs() const {
  if (recent_intervals_ns_.size() < kIntervalsNeeded) return 0;
  std::vector<int64_t> sorted = recent_intervals_ns_;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  return sorted[sorted.size() / 2];
}

double ScanIntervalClock::GapBefore(int64_t scan_end_ns) const {
  const int64_t interval = scan_end_ns - previous_scan_end_ns_;
  if (previous_scan_end_ns_ == 0 || interval <= 0) return 0.0;
  const int64_t usual = UsualIntervalNs();
  return usual > 0 && interval > kGapIntervals * usual ? NanosToSeconds(interval - usual) : 0.0;
}

double ScanIntervalClock::Tick(int64_t scan_end_ns) {
  const double gap_s = GapBefore(scan_end_ns);
  const int64_t interval = scan_end_ns - previous_scan_end_ns_;
  const bool first = previous_scan_end_ns_ == 0;
  previous_scan_end_ns_ = scan_end_ns;
  if (first || interval <= 0 || gap_s > 0.0) return gap_s;
  recent_intervals_ns_.push_back(interval);
  if (recent_intervals_ns_.size() > kIntervalsKept) {
    recent_intervals_ns_.erase(recent_intervals_ns_.begin());
  }
  return 0.0;
}

}  // namespace hylo::odometry
