#include "hylo/odometry/scan_preprocessor.h"

#include <algorithm>

#include "hylo/common/check.h"
#include "hylo/common/option_checks.h"
#include "hylo/common/time.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::odometry {
namespace {

// Every `stride`-th return of each ring, in the driver's order (a ring's returns arrive in
// time order, so this thins each scan line evenly along the sweep).
std::vector<std::size_t> StridedIndices(const LidarScan& scan, int stride) {
  std::vector<std::size_t> kept;
  kept.reserve(scan.points.size() / static_cast<std::size_t>(stride) + 1);
  std::vector<int> seen_in_ring;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const uint16_t ring = scan.points[i].ring;
    if (ring >= seen_in_ring.size()) seen_in_ring.resize(ring + 1u, 0);
    if (seen_in_ring[ring]++ % stride == 0) kept.push_back(i);
  }
  return kept;
}

// The scan's points kept by the ring stride, then by uniform sampling of their raw positions
// (times and rings kept).
LidarScan DownsampleScan(const LidarScan& scan, double voxel_m, int stride) {
  LidarScan kept;
  kept.t_ns = scan.t_ns;
  kept.end_t_ns = scan.end_t_ns;
  kept.frame_id = scan.frame_id;
  std::vector<std::size_t> candidates;
  PointCloud positions;
  if (stride > 1) {
    candidates = StridedIndices(scan, stride);
    positions.reserve(candidates.size());
    for (std::size_t i : candidates) positions.push_back(scan.points[i].position_lidar);
  } else {
    positions = estimation::PointsOf(scan);
  }
  const std::vector<std::size_t> sampled =
      registration::UniformSampleIndices(positions, static_cast<float>(voxel_m));
  kept.points.reserve(sampled.size());
  for (std::size_t j : sampled) kept.points.push_back(scan.points[stride > 1 ? candidates[j] : j]);
  return kept;
}

}  // namespace

bool PreprocessOptions::IsValid(std::string* why) const {
  if (!CheckNonNegative("min_range_m", min_range_m, why)) return false;
  if (!(std::isfinite(max_range_m) && max_range_m > min_range_m)) {
    return FailOption("max_range_m", max_range_m, "must be finite and > min_range_m", why);
  }
  return CheckPositive("max_point_offset_s", max_point_offset_s, why) &&
         CheckNonNegative("scan_voxel_m", scan_voxel_m, why) &&
         CheckAtLeast("point_stride", point_stride, 1, "(1 = keep every return)", why) &&
         CheckAtLeast("min_points", min_points, 1, "", why);
}

ScanSanitizeReport SanitizeScan(LidarScan* scan, float min_range_m, float max_range_m,
                                int64_t max_offset_ns) {
  HYLO_CHECK(scan != nullptr);
  ScanSanitizeReport report;
  const float min_sq = min_range_m * min_range_m;
  const float max_sq = max_range_m * max_range_m;
  auto keep = [&](const ScanPoint& p) {
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

ScanPreprocessor::ScanPreprocessor(const PreprocessOptions& options, bool deskew)
    : options_(options), deskew_(deskew && options.deskew) {}

ScanSanitizeReport ScanPreprocessor::Clean(LidarScan* scan) const {
  return SanitizeScan(scan, static_cast<float>(options_.min_range_m),
                      static_cast<float>(options_.max_range_m),
                      SecondsToNanos(options_.max_point_offset_s));
}

bool ScanPreprocessor::Prepare(LidarScan scan, const std::vector<int64_t>& imu_knots_ns,
                               const estimation::Estimator& estimator, PreparedScan* prepared,
                               ScanSanitizeReport* report) const {
  *report = Clean(&scan);
  if (static_cast<int>(scan.points.size()) < options_.min_points) return false;
  prepared->cleaned = std::move(scan);
  const LidarScan& cleaned = prepared->cleaned;
  prepared->motion = deskew_ ? estimation::SweepMotion(cleaned.t_ns, cleaned.end_t_ns, estimator, imu_knots_ns)
                             : estimation::SweepMotion();
  // Downsample first, then undistort only the kept points: the voxel (0.5 m) is much larger
  // than the motion within one sweep, and undistortion is the per-point cost.
  const LidarScan kept = DownsampleScan(cleaned, options_.scan_voxel_m, options_.point_stride);
  prepared->registration.t_ns = cleaned.end_t_ns;
  prepared->registration.points_lidar = prepared->motion.ToSweepEnd(kept);
  return true;
}

PointCloud ScanPreprocessor::Deskewed(const PreparedScan& prepared, double voxel_m) const {
  if (voxel_m <= 0.0) return prepared.motion.ToSweepEnd(prepared.cleaned);
  return prepared.motion.ToSweepEnd(DownsampleScan(prepared.cleaned, voxel_m, 1));
}

}  // namespace hylo::odometry
