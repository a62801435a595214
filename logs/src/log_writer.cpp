#include "hylo/logs/log_writer.h"

#include "hylo/logs/bag_writer.h"
#include "hylo/logs/rosbag2_writer.h"

namespace hylo::logs {
namespace {

constexpr LogFormat kFormats[] = {LogFormat::kRos1, LogFormat::kSqlite3, LogFormat::kMcap,
                                  LogFormat::kMcapZstd, LogFormat::kMcapLz4};

}  // namespace

std::string ToString(LogFormat format) {
  switch (format) {
    case LogFormat::kRos1:
      return "ros1";
    case LogFormat::kSqlite3:
      return "sqlite3";
    case LogFormat::kMcap:
      return "mcap";
    case LogFormat::kMcapZstd:
      return "mcap-zstd";
    case LogFormat::kMcapLz4:
      return "mcap-lz4";
  }
  return "unknown";
}

bool ParseLogFormat(const std::string& name, LogFormat* format) {
  for (const LogFormat f : kFormats) {
    if (ToString(f) == name) {
      *format = f;
      return true;
    }
  }
  return false;
}

std::string LogPathFor(const std::string& stem, LogFormat format) {
  return format == LogFormat::kRos1 ? stem + ".bag" : stem;
}

void LogWriter::WriteScan(const std::string& topic, const LidarScan& scan,
                          PointTimeConvention layout, const std::string& frame_id) {
  PointCloud2Message cloud = EncodePointCloud2(scan, layout);
  cloud.frame_id = frame_id;
  WriteCloud(topic, cloud, scan.end_t_ns);
}

std::unique_ptr<LogWriter> CreateLogWriter(const std::string& path, LogFormat format) {
  if (format == LogFormat::kRos1) return std::make_unique<BagWriter>(path);
  Rosbag2WriterOptions options;
  options.storage =
      format == LogFormat::kSqlite3 ? Rosbag2Storage::kSqlite3 : Rosbag2Storage::kMcap;
  options.mcap_compression = format == LogFormat::kMcapZstd  ? "zstd"
                             : format == LogFormat::kMcapLz4 ? "lz4"
                                                             : "";
  return std::make_unique<Rosbag2Writer>(path, options);
}

}  // namespace hylo::logs
