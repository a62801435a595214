// `hylo map --log LOG --config C --out DIR [--json PATH]`: SLAM from scratch with the
// configured back-end. Writes the trajectory of the IMU frame in the map frame (TUM), the map
// (PCD; and map_dense.pcd, every registered scan at output.dense_map_voxel_m, the input of
// offline crafting), per-scan timing (CSV), the effective configuration and a JSON summary.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <sys/resource.h>

#include "commands.h"
#include "hylo/common/time.h"
#include "hylo/config/run_config.h"
#include "hylo/estimation/odometry_pipeline.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/log_reader.h"
#include "hylo/io/progress.h"
#include "hylo/io/trajectory_io.h"
#include "hylo/mapping/ikd_tree.h"

namespace hylo::cli {
namespace {

struct MapArgs {
  std::string log, config, out, json;
};

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t i = static_cast<std::size_t>(q * (values.size() - 1) + 0.5);
  return values[std::min(i, values.size() - 1)];
}

void WriteTiming(const std::string& path, const std::vector<estimation::ScanResult>& results) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  out << "t_s,points,downsampled,matches,iterations,converged,applied,degenerate,"
         "deskew_ms,update_ms,map_ms,total_ms,map_points\n";
  for (const auto& r : results) {
    out << io::FormatNsAsSeconds(r.t_ns) << ',' << r.raw_points << ',' << r.downsampled_points
        << ',' << r.update.num_matches << ',' << r.update.iterations << ','
        << r.update.converged << ',' << r.update.applied << ',' << r.update.degenerate << ','
        << r.deskew_ms << ',' << r.update_ms << ',' << r.map_ms << ',' << r.total_ms << ','
        << r.map_points << '\n';
  }
}

io::Json Summarize(const MapArgs& args, const config::RunConfig& config,
                   const estimation::OdometryPipeline& pipeline,
                   const std::vector<estimation::ScanResult>& results, double elapsed_s) {
  std::vector<double> total_ms;
  double path_m = 0.0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    total_ms.push_back(results[i].total_ms);
    if (i > 0) {
      path_m += (results[i].state.p_map_imu - results[i - 1].state.p_map_imu).norm();
    }
  }
  const estimation::PipelineCounters c = pipeline.counters();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  io::Json j;
  j["log"] = args.log;
  j["backend"] = config.backend;
  j["imu"] = config.imu.enabled;
  j["scans_processed"] = c.scans_processed;
  j["scans_before_init"] = c.scans_before_init;
  j["scans_too_small"] = c.scans_too_small;
  j["scans_not_applied"] = c.scans_not_applied;
  j["scans_degenerate"] = c.scans_degenerate;
  j["points_dropped_sanitize"] = c.points_dropped_sanitize;
  j["queue"]["imu_duplicates"] = c.queue.imu_duplicates;
  j["queue"]["imu_stale"] = c.queue.imu_stale;
  j["queue"]["scan_duplicates"] = c.queue.scan_duplicates;
  j["queue"]["scan_stale"] = c.queue.scan_stale;
  j["queue"]["imu_gaps"] = c.queue.imu_gaps;
  j["queue"]["longest_imu_gap_s"] = NanosToSeconds(c.queue.longest_imu_gap_ns);
  j["path_length_m"] = path_m;
  j["map_points"] = pipeline.map().Size();
  j["ms_per_scan_median"] = Percentile(total_ms, 0.5);
  j["ms_per_scan_p99"] = Percentile(total_ms, 0.99);
  j["peak_memory_mb"] = usage.ru_maxrss / 1024.0;
  j["elapsed_s"] = elapsed_s;
  return j;
}

void RunMap(const MapArgs& args) {
  const config::RunConfig config = config::LoadRunConfig(args.config);
  std::filesystem::create_directories(args.out);
  config::SaveRunConfig(args.out + "/config.yaml", config);
  estimation::OdometryPipeline pipeline(config.PipelineOptions());
  auto log = io::OpenLog(args.log, config.LogOptions());
  std::vector<estimation::ScanResult> results;
  // The dense map (offline crafting's input) keeps one point per voxel, nearest the voxel
  // centre, through the ikd-tree's downsampling insert: memory grows with the surface, not
  // with the number of scans.
  const float dense_voxel_m = static_cast<float>(config.output.dense_map_voxel_m);
  mapping::IkdTree dense_map{mapping::IkdTree::Options()};
  std::size_t dense_consumed = 0;
  auto consume_dense = [&] {
    for (; dense_consumed < results.size(); ++dense_consumed) {
      auto& points = results[dense_consumed].registered_points_map;
      if (dense_voxel_m > 0.f && !points.empty()) dense_map.Insert(points, dense_voxel_m);
      registration::PointCloud().swap(points);  // results keep only the pose and timing
    }
  };
  io::Progress progress("map", 0);
  io::LogMessage message;
  std::size_t scans = 0;
  while (log->Next(&message)) {
    if (message.kind == io::LogMessage::Kind::kImu) {
      pipeline.AddImu(message.imu);
      continue;
    }
    pipeline.AddScan(std::move(message.scan));
    pipeline.Process(&results);
    consume_dense();
    progress.Update(++scans);
    if (pipeline.status() == estimation::OdometryPipeline::Status::kFailed) break;
  }
  pipeline.Process(&results, true);
  consume_dense();
  progress.Finish();
  if (pipeline.status() == estimation::OdometryPipeline::Status::kFailed) {
    throw std::runtime_error(args.log + ": " + pipeline.message());
  }
  if (results.empty()) throw std::runtime_error(args.log + ": no scan was processed");
  std::vector<io::StampedPose> trajectory;
  for (const auto& r : results) {
    io::StampedPose p;
    p.t_ns = r.t_ns;
    p.position = r.state.p_map_imu;
    p.orientation = r.state.R_map_imu.unit_quaternion();
    trajectory.push_back(p);
  }
  io::WriteTum(args.out + "/trajectory.tum", trajectory);
  io::CloudFile map;
  for (const Eigen::Vector3f& p : pipeline.map().Flatten()) {
    map.positions.push_back(p.cast<double>());
  }
  io::WriteCloud(args.out + "/map.pcd", map);
  if (dense_voxel_m > 0.f) {
    io::CloudFile dense;
    for (const Eigen::Vector3f& p : dense_map.Flatten()) dense.positions.push_back(p.cast<double>());
    io::WriteCloud(args.out + "/map_dense.pcd", dense, io::CloudEncoding::kBinaryCompressed);
  }
  WriteTiming(args.out + "/timing.csv", results);
  const io::Json summary =
      Summarize(args, config, pipeline, results, progress.ElapsedSeconds());
  io::WriteJsonFile(args.out + "/summary.json", summary);
  MaybeWriteJson(args.json, summary);
  std::printf("%zu scans, path %.1f m, map %zu points, %.2f ms/scan median, %.2f p99\n",
              results.size(), summary.Find("path_length_m")->AsNumber(),
              pipeline.map().Size(), summary.Find("ms_per_scan_median")->AsNumber(),
              summary.Find("ms_per_scan_p99")->AsNumber());
}

}  // namespace

void AddMapCommand(CLI::App& root) {
  auto args = std::make_shared<MapArgs>();
  CLI::App* cmd = root.add_subcommand("map", "SLAM from scratch: trajectory, map, timing");
  cmd->add_option("--log", args->log, "ROS1 bag or scan folder")->required();
  cmd->add_option("--config", args->config, "run configuration (YAML)")->required();
  cmd->add_option("--out", args->out, "output directory")->required();
  cmd->add_option("--json", args->json, "also write the summary to this JSON file");
  cmd->callback([args]() { RunMap(*args); });
}

}  // namespace hylo::cli
