// `hylo convert --in LOG --out PATH [--format F] [--config C] [--lidar-topic T] [--imu-topic T]
// [--time-convention C]`: a log rewritten in another format (ROS1 bag <-> ROS 2 recording,
// sqlite3 <-> MCAP), its lidar and IMU streams as hylo reads them (logs::ConvertLog).

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "commands.h"
#include "hylo/config/run_config.h"
#include "hylo/io/progress.h"
#include "hylo/logs/log_convert.h"

namespace hylo::cli {
namespace {

struct ConvertArgs {
  std::string in, out, format, config_path, lidar_topic, imu_topic, time_convention, json_path;
  bool no_imu = false;
};

/// The format named, or the one the output's name implies: .bag -> ros1, else MCAP (ROS 2's
/// default storage since Iron).
logs::LogFormat OutputFormat(const ConvertArgs& args) {
  logs::LogFormat format = logs::LogFormat::kMcap;
  if (!args.format.empty()) {
    logs::ParseLogFormat(args.format, &format);  // checked by the option
  } else if (std::filesystem::path(args.out).extension() == ".bag") {
    format = logs::LogFormat::kRos1;
  }
  return format;
}

logs::LogReadOptions ReadOptions(const ConvertArgs& args) {
  logs::LogReadOptions options;
  if (!args.config_path.empty()) options = config::LoadRunConfig(args.config_path).LogOptions();
  if (!args.lidar_topic.empty()) options.lidar_topic = args.lidar_topic;
  if (!args.imu_topic.empty()) options.imu_topic = args.imu_topic;
  if (args.no_imu) options.imu_topic.clear();
  if (!args.time_convention.empty() &&
      !logs::ParsePointTimeConvention(args.time_convention, &options.time_convention)) {
    throw std::runtime_error("--time-convention: unknown convention '" + args.time_convention +
                             "'");
  }
  return options;
}

void Run(const ConvertArgs& args) {
  const logs::LogFormat format = OutputFormat(args);
  std::error_code ec;
  if (std::filesystem::exists(args.out, ec) &&
      !(std::filesystem::is_directory(args.out, ec) && std::filesystem::is_empty(args.out, ec))) {
    throw std::runtime_error("--out '" + args.out + "' exists; convert writes a new log");
  }
  const auto start = std::chrono::steady_clock::now();
  io::Progress progress("convert", 0);
  const logs::ConvertSummary s = logs::ConvertLog(args.in, args.out, format, ReadOptions(args),
                                                  [&](std::size_t n) { progress.Update(n); });
  progress.Finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s -> %s (%s): %zu scans (%s layout), %zu IMU samples in %.2f s\n", args.in.c_str(),
              args.out.c_str(), logs::ToString(format).c_str(), s.scans,
              logs::ToString(s.layout).c_str(), s.imu_samples, seconds);
  const logs::LogReadCounters& c = s.counters;
  if (c.dropped_non_finite_points + c.dropped_non_finite_imu > 0) {
    std::printf("not written: %zu NaN/inf points, %zu NaN/inf IMU samples\n",
                c.dropped_non_finite_points, c.dropped_non_finite_imu);
  }
  if (s.recovery) {
    std::fprintf(stderr, "warning: %s: %s\n", args.in.c_str(), s.recovery->Summary().c_str());
  }
  io::Json j = io::Json::object();
  j["in"] = args.in;
  j["out"] = args.out;
  j["format"] = logs::ToString(format);
  j["scans"] = s.scans;
  j["imu_samples"] = s.imu_samples;
  j["layout"] = logs::ToString(s.layout);
  j["wall_s"] = seconds;
  MaybeWriteJson(args.json_path, j);
}

}  // namespace

void AddConvertCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "convert", "Rewrite a log in another format: ROS1 bag <-> ROS 2 recording (sqlite3, MCAP)");
  static ConvertArgs args;
  cmd->add_option("--in", args.in, "log to read: any hylo reads (bag, rosbag2, .mcap, folder)")
      ->required();
  cmd->add_option("--out", args.out,
                  "log to write: a .bag, a rosbag2 directory, or a .mcap file (must not exist)")
      ->required();
  cmd->add_option("--format", args.format,
                  "ros1, sqlite3, mcap, mcap-zstd, mcap-lz4 (default: ros1 for .bag, else mcap)")
      ->check(CLI::IsMember({"ros1", "sqlite3", "mcap", "mcap-zstd", "mcap-lz4"}));
  cmd->add_option("--config", args.config_path, "run configuration: its lidar and imu topics");
  cmd->add_option("--lidar-topic", args.lidar_topic, "lidar topic (default /points)");
  cmd->add_option("--imu-topic", args.imu_topic, "IMU topic (default /imu)");
  cmd->add_flag("--no-imu", args.no_imu, "copy the lidar topic only");
  cmd->add_option("--time-convention", args.time_convention,
                  "per-point time of the input: auto, velodyne, ouster, hesai, robosense, livox, "
                  "none (default auto)");
  cmd->add_option("--json", args.json_path, "write a JSON summary here");
  cmd->callback([] { Run(args); });
}

}  // namespace hylo::cli
