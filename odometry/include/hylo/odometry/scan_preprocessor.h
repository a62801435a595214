#pragma once
// Scan clean-up before registration (section `preprocess:` of a run configuration), done once
// per sweep: drop unusable returns, keep every n-th return of each ring, uniformly sample, and
// deskew with the back-end's prediction. The sweep's motion is kept, so any other subset of the
// sweep (the dense copy for map outputs, the whole sweep for a relocalization) is deskewed the
// same way without predicting again.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/estimation/estimator.h"
#include "hylo/estimation/undistortion.h"

namespace hylo::odometry {

struct PreprocessOptions {
  double min_range_m = 0.5;         ///< closer returns are dropped (vehicle body), m (>= 0)
  double max_range_m = 100.0;       ///< farther returns are dropped, m (> min_range_m)
  double max_point_offset_s = 0.2;  ///< per-point times beyond this after the start are bad, s
                                    ///< (> 0)
  double scan_voxel_m = 0.5;        ///< uniform-sampling voxel of the scan, m (0 = keep all)
  int point_stride = 1;             ///< before the voxel, keep every n-th return of each ring
                                    ///< (FAST-LIO2's point_filter_num): less work per scan
                                    ///< on dense sensors, sparser far surfaces (>= 1)
  int min_points = 100;             ///< fewer points after clean-up: the scan is skipped (>= 1)
  bool deskew = true;               ///< undistort with the IMU (always off without IMU)
  bool IsValid(std::string* why) const;
};

/// What the clean-up removed, for the per-run counters.
struct ScanSanitizeReport {
  std::size_t dropped_non_finite = 0;    ///< NaN or inf coordinates
  std::size_t dropped_out_of_range = 0;  ///< closer than min or farther than max range
  std::size_t dropped_bad_time = 0;      ///< negative offsets or offsets beyond max_offset_ns

  std::size_t total() const { return dropped_non_finite + dropped_out_of_range + dropped_bad_time; }
};

/// Drops non-finite points, points outside [min_range_m, max_range_m] and points whose time
/// offset is negative or above `max_offset_ns`; then sets end_t_ns from the remaining points
/// (or to t_ns when none remain). Never throws on bad data: it counts.
ScanSanitizeReport SanitizeScan(LidarScan* scan, float min_range_m, float max_range_m,
                                int64_t max_offset_ns);

/// One sweep ready for the update.
struct PreparedScan {
  LidarScan cleaned;          ///< every usable return, as measured (lidar frame, own times)
  estimation::DeskewedScan registration;  ///< the strided, sampled returns at the sweep end: what the
                              ///< back-end registers
  estimation::SweepMotion motion;         ///< the sweep's motion (none without IMU or deskewing)
};

class ScanPreprocessor {
 public:
  /// `deskew`: undistort with the IMU prediction (needs an IMU; options.deskew must be set too).
  ScanPreprocessor(const PreprocessOptions& options, bool deskew);

  /// Drops the unusable returns of `scan` (see SanitizeScan).
  ScanSanitizeReport Clean(LidarScan* scan) const;

  /// Cleans `scan`, predicts its motion with `estimator` at `imu_knots_ns`, and samples and
  /// deskews the registration subset. False when fewer than min_points returns are usable.
  bool Prepare(LidarScan scan, const std::vector<int64_t>& imu_knots_ns, const estimation::Estimator& estimator,
               PreparedScan* prepared, ScanSanitizeReport* report) const;

  /// The cleaned sweep uniformly sampled at `voxel_m` (0 = every return), deskewed like the
  /// registration subset.
  PointCloud Deskewed(const PreparedScan& prepared, double voxel_m) const;

 private:
  PreprocessOptions options_;
  bool deskew_;
};

}  // namespace hylo::odometry
