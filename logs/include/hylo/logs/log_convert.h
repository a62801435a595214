#pragma once
// Rewriting a log in another format: what hylo reads of it (the lidar and IMU streams), written
// as those drivers publish them, so that a recording of one ROS generation runs through tools of
// the other, and the same session can be compared across formats.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "hylo/logs/log_reader.h"
#include "hylo/logs/log_writer.h"

namespace hylo::logs {

struct ConvertSummary {
  std::size_t imu_samples = 0;                              ///< written
  std::size_t scans = 0;                                    ///< written
  PointTimeConvention layout = PointTimeConvention::kNone;  ///< the scans' field layout
  LogReadCounters counters;             ///< what the reader counted (drops included)
  std::optional<LogRecovery> recovery;  ///< set when the input was damaged
};

/// Reads `in` (OpenLog with `options`; accelerations as stored, whatever
/// options.imu_accel_scale says) and writes its IMU samples and scans to `out` in `format`, on
/// the same topics: IMU samples at their stamps; scans in the PointCloud2 layout of the
/// convention read (Velodyne, Ouster, ..., Livox for a CustomMsg input; kNone: x y z intensity),
/// each at its end time. Not copied: other topics, points and samples the reader drops
/// (counted), fields hylo does not read. On any error the exception propagates and nothing is
/// left at `out`. `progress` (optional) gets the number of messages written so far.
ConvertSummary ConvertLog(const std::string& in, const std::string& out, LogFormat format,
                          LogReadOptions options,
                          const std::function<void(std::size_t)>& progress = {});

}  // namespace hylo::logs
