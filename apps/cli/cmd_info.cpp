// `hylo info LOG`: what a log holds, before anyone runs an estimator on it. A ROS1 bag or a
// ROS 2 recording shows its topics, counts, rates, time span, point fields and the per-point
// time convention it announces (a ROS 2 recording also its storage and compression); a scan
// folder shows its scan count, format, fields and time span.

#include <cstdio>
#include <optional>
#include <filesystem>
#include <sstream>

#include "commands.h"
#include "hylo/common/time.h"
#include "hylo/logs/bag_reader.h"
#include "hylo/logs/log_reader.h"
#include "hylo/logs/rosbag2_reader.h"
#include "hylo/logs/scan_folder.h"
#include "hylo/run/run_log.h"

namespace hylo::cli {
namespace {

std::string FieldList(const std::vector<logs::PointFieldInfo>& fields) {
  std::ostringstream os;
  for (const auto& f : fields) {
    os << (os.tellp() > 0 ? " " : "") << f.name << ":" << logs::PointFieldDatatypeName(f.datatype);
    if (f.count != 1) os << "[" << f.count << "]";
  }
  return os.str();
}

/// The topic lines of a bag or a ROS 2 recording, and their JSON.
io::Json TopicsToTerminal(const std::vector<logs::BagTopicDescription>& topics) {
  io::Json list = io::Json::array();
  for (const auto& t : topics) {
    std::printf("  %-28s %-26s %7zu msgs  %8.2f Hz  %.3f .. %.3f s\n", t.name.c_str(),
                t.type.c_str(), t.message_count, t.mean_rate_hz, NanosToSeconds(t.first_stamp_ns),
                NanosToSeconds(t.last_stamp_ns));
    io::Json topic;
    topic["name"] = t.name;
    topic["type"] = t.type;
    topic["message_count"] = t.message_count;
    topic["rate_hz"] = t.mean_rate_hz;
    topic["first_stamp_s"] = NanosToSeconds(t.first_stamp_ns);
    topic["last_stamp_s"] = NanosToSeconds(t.last_stamp_ns);
    if (!t.point_fields.empty()) {
      const std::string fields = FieldList(t.point_fields);
      std::printf("      point fields: %s\n      per-point time: %s\n", fields.c_str(),
                  logs::ToString(t.detected_convention).c_str());
      topic["point_fields"] = fields;
      topic["time_convention"] = logs::ToString(t.detected_convention);
    }
    list.push_back(std::move(topic));
  }
  return list;
}

/// A damaged log: what a run would use of it.
void RecoveryToTerminal(const std::optional<logs::LogRecovery>& recovery, io::Json* json) {
  if (!recovery) return;
  std::printf("  damaged: %s\n", recovery->Summary().c_str());
  (*json)["recovery"] = run::LogRecoveryJson(*recovery);
}

io::Json DescribeBagToTerminal(const std::string& path) {
  const logs::BagDescription bag = logs::DescribeBag(path);
  std::printf("ROS1 bag %s\n  size %.1f MB, %zu messages, %.3f s (receive time %.3f .. %.3f)\n",
              path.c_str(), bag.file_size_bytes / 1e6, bag.message_count, bag.duration_s,
              NanosToSeconds(bag.start_ns), NanosToSeconds(bag.end_ns));
  io::Json json;
  json["kind"] = "bag";
  json["path"] = path;
  json["message_count"] = bag.message_count;
  json["duration_s"] = bag.duration_s;
  RecoveryToTerminal(bag.recovery, &json);
  json["topics"] = TopicsToTerminal(bag.topics);
  return json;
}

io::Json DescribeRosbag2ToTerminal(const std::string& path) {
  const logs::Rosbag2Description bag = logs::DescribeRosbag2(path);
  const std::string metadata = bag.metadata_version > 0
                                   ? "metadata.yaml version " + std::to_string(bag.metadata_version)
                                   : "no metadata.yaml";
  std::printf("ROS 2 recording %s\n  storage %s, compression %s, %zu file(s), %s\n",
              path.c_str(), bag.storage.c_str(), bag.compression.c_str(), bag.files.size(),
              metadata.c_str());
  std::printf("  size %.1f MB, %zu messages, %.3f s (receive time %.3f .. %.3f)\n",
              bag.size_bytes / 1e6, bag.message_count, bag.duration_s,
              NanosToSeconds(bag.start_ns), NanosToSeconds(bag.end_ns));
  io::Json json;
  json["kind"] = "rosbag2";
  json["path"] = path;
  json["storage"] = bag.storage;
  json["compression"] = bag.compression;
  json["files"] = bag.files;
  json["metadata_version"] = bag.metadata_version;
  json["message_count"] = bag.message_count;
  json["duration_s"] = bag.duration_s;
  RecoveryToTerminal(bag.recovery, &json);
  json["topics"] = TopicsToTerminal(bag.topics);
  return json;
}

io::Json DescribeFolderToTerminal(const std::string& path) {
  const logs::ScanFolderDescription folder = logs::DescribeScanFolder(path);
  std::ostringstream fields;
  for (const auto& f : folder.point_fields) fields << (fields.tellp() > 0 ? " " : "") << f;
  std::printf("scan folder %s\n  %zu scans (%s, %s), first scan %zu points, fields: %s\n",
              path.c_str(), folder.scan_count, folder.format.c_str(), folder.encoding.c_str(),
              folder.first_scan_points, fields.str().c_str());
  std::printf("  times from %s; span %.3f s (%.3f .. %.3f)\n", folder.time_source.c_str(),
              folder.time_span_s, NanosToSeconds(folder.first_t_ns),
              NanosToSeconds(folder.last_t_ns));
  std::printf("  poses: %s (%zu scans with a pose, %zu without)\n",
              folder.pose_file.empty() ? "none" : folder.pose_file.c_str(),
              folder.scans_with_pose, folder.scans_without_pose);
  std::printf("  per-point time: none (deskewing impossible; use imu: none)\n");
  io::Json json;
  json["kind"] = "scan_folder";
  json["path"] = path;
  json["scan_count"] = folder.scan_count;
  json["format"] = folder.format;
  json["point_fields"] = fields.str();
  json["time_source"] = folder.time_source;
  json["time_span_s"] = folder.time_span_s;
  json["pose_file"] = folder.pose_file;
  json["scans_with_pose"] = folder.scans_with_pose;
  json["time_convention"] = "none";
  return json;
}

}  // namespace

void AddInfoCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "info", "Describe a log: a ROS1 bag, a ROS 2 recording (rosbag2, .mcap) or a scan folder");
  static std::string log_path;
  static std::string json_path;
  cmd->add_option("LOG", log_path,
                  "ROS1 bag, rosbag2 directory (sqlite3 or MCAP), .mcap file, or scan folder "
                  "(PCD/PLY/KITTI .bin + poses)")
      ->required();
  cmd->add_option("--json", json_path, "write the description as JSON to this file");
  cmd->callback([] {
    if (!std::filesystem::exists(log_path)) {
      throw std::runtime_error("'" + log_path + "' does not exist");
    }
    const io::Json summary = logs::IsRosbag2(log_path) ? DescribeRosbag2ToTerminal(log_path)
                             : std::filesystem::is_directory(log_path)
                                 ? DescribeFolderToTerminal(log_path)
                                 : DescribeBagToTerminal(log_path);
    MaybeWriteJson(json_path, summary);
  });
}

}  // namespace hylo::cli
