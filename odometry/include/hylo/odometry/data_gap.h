#pragma once
// Gaps in the data, told from the data's own rate: a scan interval against the usual one (the
// median of the recent intervals), so that the same rule holds for any lidar.

#include <cstdint>
#include <vector>

namespace hylo::odometry {

class ScanIntervalClock {
 public:
  /// Ticks for the scan ending at `scan_end_ns`: the time without data before it (the interval
  /// beyond the usual one) when the interval exceeds kGapIntervals usual ones, else 0, s. A gap's
  /// interval does not join the usual ones.
  double Tick(int64_t scan_end_ns);
  /// What Tick would say for `scan_end_ns`, without ticking.
  double GapBefore(int64_t scan_end_ns) const;
  /// The usual interval (median of the recent ones), ns; 0 until a few scans have been seen.
  int64_t UsualIntervalNs() const;

  /// A scan or two dropped is tracked through as before; more is a gap.
  static constexpr double kGapIntervals = 3.0;

 private:
  int64_t previous_scan_end_ns_ = 0;
  std::vector<int64_t> recent_intervals_ns_;
};

}  // namespace hylo::odometry
