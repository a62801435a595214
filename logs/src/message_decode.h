#pragma once
// Private to hylo_logs: what every log reader does with the messages it finds, whatever the
// format (ROS1 bag, rosbag2, MCAP): topic checks with errors that list what the log holds, the
// first scan decoded at open, and PointCloud2Message / ImuSample -> LogMessage with counted
// drops. The format readers only turn their bytes into these plain types.

#include <map>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/logs/log_reader.h"
#include "hylo/logs/pointcloud2.h"

namespace hylo::logs::detail {

/// topic -> types of its connections (normally exactly one).
using TopicTypes = std::map<std::string, std::vector<std::string>>;

/// Throws naming the file when `topic` is missing (listing the topics there are) or of a type
/// not in `types` ("expected A" or "expected A or B").
void RequireTopic(const std::string& path, const TopicTypes& topics, const std::string& topic,
                  const std::vector<std::string>& types);

/// The first scan, decoded once at open: resolves kAuto and reports a cloud without x/y/z (or
/// without the configured time field) then, not somewhere into the run. Returns the convention.
PointTimeConvention CheckFirstCloud(const PointCloud2Message& first, PointTimeConvention convention,
                                    const std::string& path, const std::string& topic);

/// A scan message (empty scans are delivered and counted).
void DecodeScan(const PointCloud2Message& cloud, PointTimeConvention convention,
                LogMessage* message, LogReadCounters* counters);

/// An IMU sample, its accelerations already in m/s^2; false (skipped and counted) for NaN/inf.
bool AcceptImu(const ImuSample& imu, LogMessage* message, LogReadCounters* counters);

}  // namespace hylo::logs::detail
