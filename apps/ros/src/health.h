#pragma once
// The node's health topic: one JSON line (std_msgs/String) per processed scan, so any tool
// (rostopic echo, a Python monitor, a logger) reads it without custom messages. No ROS here.

#include <cstdint>
#include <string>

#include "hylo/localization/localization.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "input_queue.h"

namespace hylo::rosnode {

/// What the localizer is doing, as the health topic names it.
enum class HealthState {
  kInitialising,   ///< IMU at rest / ICP initializer, no pose yet
  kLocalized,      ///< running (SLAM: tracking in its own map)
  kLost,           ///< health bad for lost_after_scans scans; automatic relocalization pending
  kRelocalizing,   ///< a user relocalization (service or /initialpose) is pending
  kFailed,         ///< the pipeline stopped (see message)
};

/// "initialising", "localized", "lost", "relocalizing", "failed".
std::string ToString(HealthState state);

/// The state from the pipeline's status and whether a user relocalization is pending.
HealthState StateOf(odometry::OdometryPipeline::Status status, bool relocalization_pending);

struct HealthReport {
  HealthState state = HealthState::kInitialising;
  int64_t t_ns = 0;                    ///< stamp of the last processed scan (0: none yet), ns
  bool localizing = false;             ///< a prior map is used (else SLAM)
  std::string backend;                 ///< ieskf | sliding_window
  localization::ScanHealth scan;         ///< fit of the last scan (fitness, inliers, matches)
  bool update_applied = false;         ///< the last scan's update was applied
  odometry::PipelineCounters pipeline;  ///< processed, skipped, the pipeline's queue
  InputCounters input;                 ///< the node's bounded queue: late / dropped messages
  std::size_t map_points = 0;          ///< points in the map after the last scan
  std::string last_event;              ///< the last LocalizationEvent, "kind: message"
  std::string message;                 ///< why the pipeline failed, else empty
};

/// One line of JSON; NaN fitness is written as null.
std::string HealthJson(const HealthReport& report);

}  // namespace hylo::rosnode
