#include "hylo/estimation/measurements.h"

#include <algorithm>
#include <cmath>

#include "hylo/common/check.h"

namespace hylo::estimation {

ScanSanitizeReport SanitizeScan(LidarScan* scan, float min_range_m, float max_range_m,
                                int64_t max_offset_ns) {
  HYLO_CHECK(scan != nullptr);
  ScanSanitizeReport report;
  const float min_sq = min_range_m * min_range_m;
  const float max_sq = max_range_m * max_range_m;
  auto keep = [&](const registration::ScanPoint& p) {
    if (!p.position_lidar.allFinite()) {
      ++report.dropped_non_finite;
      return false;
    }
    const float r2 = p.position_lidar.squaredNorm();
    if (r2 < min_sq || r2 > max_sq) {
      ++report.dropped_out_of_range;
      return false;
    }
    if (p.offset_ns < 0 || p.offset_ns > max_offset_ns) {
      ++report.dropped_bad_time;
      return false;
    }
    return true;
  };
  auto& pts = scan->points;
  pts.erase(std::remove_if(pts.begin(), pts.end(), [&](const auto& p) { return !keep(p); }),
            pts.end());
  int32_t last_offset_ns = 0;
  for (const auto& p : pts) last_offset_ns = std::max(last_offset_ns, p.offset_ns);
  scan->end_t_ns = scan->t_ns + last_offset_ns;
  return report;
}

}  // namespace hylo::estimation
