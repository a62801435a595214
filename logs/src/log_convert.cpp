#include "hylo/logs/log_convert.h"

#include <filesystem>

namespace hylo::logs {

ConvertSummary ConvertLog(const std::string& in, const std::string& out, LogFormat format,
                          LogReadOptions options,
                          const std::function<void(std::size_t)>& progress) {
  options.imu_accel_scale = 1.0;  // the units stay the driver's: the same configuration reads both
  const std::unique_ptr<LogReader> reader = OpenLog(in, options);
  ConvertSummary summary;
  summary.layout = reader->time_convention() == PointTimeConvention::kAuto
                       ? PointTimeConvention::kNone
                       : reader->time_convention();
  std::unique_ptr<LogWriter> writer = CreateLogWriter(out, format);
  try {
    LogMessage m;
    while (reader->Next(&m)) {
      if (m.kind == LogMessage::Kind::kImu) {
        writer->WriteImu(options.imu_topic, m.imu, "imu");
        ++summary.imu_samples;
      } else {
        writer->WriteScan(options.lidar_topic, m.scan, summary.layout,
                          m.scan.frame_id.empty() ? "lidar" : m.scan.frame_id);
        ++summary.scans;
      }
      if (progress) progress(summary.imu_samples + summary.scans);
    }
    writer->Close();
  } catch (...) {
    // A ROS1 bag writer closes what it has when destroyed: remove it, as rosbag2 writers do.
    writer.reset();
    std::error_code ec;
    if (format == LogFormat::kRos1) std::filesystem::remove(out, ec);
    throw;
  }
  summary.counters = reader->counters();
  if (const LogRecovery* r = reader->recovery()) summary.recovery = *r;
  return summary;
}

}  // namespace hylo::logs
