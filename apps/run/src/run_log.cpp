#include "hylo/run/run_log.h"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "hylo/common/time.h"
#include "hylo/estimation/odometry_pipeline.h"
#include "hylo/evaluation/cloud_distance.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/log_reader.h"
#include "hylo/io/progress.h"
#include "hylo/mapping/ikd_tree.h"
#include "hylo/registration/voxel_filter.h"
#include "hylo/run/prior_map_io.h"
#include "run_outputs.h"

namespace hylo::run {
namespace {

using estimation::OdometryPipeline;
using estimation::ScanResult;

io::Json EventsJson(const std::vector<estimation::LocalizationEvent>& events,
                    const Eigen::Vector3d& origin_world) {
  io::Json array = io::Json::array();
  for (const auto& e : events) {
    io::Json j;
    j["kind"] = estimation::ToString(e.kind);
    j["t_s"] = NanosToSeconds(e.t_ns);
    const Eigen::Vector3d p = e.T_map_imu.translation() + origin_world;
    j["position_m"] = io::Json::array({p.x(), p.y(), p.z()});
    const Eigen::Matrix3d& R = e.T_map_imu.linear();
    j["yaw_deg"] = std::atan2(R(1, 0), R(0, 0)) * 180.0 / M_PI;
    if (std::isfinite(e.fitness_m2)) j["fitness_m2"] = e.fitness_m2;
    if (std::isfinite(e.plane_fitness_m2)) j["plane_fitness_m2"] = e.plane_fitness_m2;
    j["inlier_ratio"] = e.inlier_ratio;
    j["message"] = e.message;
    array.push_back(j);
  }
  return array;
}

// The paper's cloud-to-cloud metric: the registered scans against the prior map.
io::Json CloudToCloudJson(const PointCloud& registered_map, const PointCloud& prior_map,
                          double max_distance_m) {
  mapping::IkdTree reference{mapping::IkdTree::Options()};
  reference.Build(prior_map);
  evaluation::CloudDistanceOptions options;
  options.max_distance_m = max_distance_m;
  const evaluation::CloudDistanceSummary s =
      evaluation::CloudToCloudDistance(registered_map, reference, options);
  io::Json j;
  j["ok"] = s.ok;
  j["mean_m"] = s.mean_m;
  j["std_m"] = s.std_m;
  j["median_m"] = s.median_m;
  j["rejected_fraction"] = s.rejected_fraction;
  j["points"] = s.num_points;
  j["max_distance_m"] = max_distance_m;
  if (!s.ok) j["message"] = s.message;
  return j;
}

}  // namespace

io::Json PipelineCountersJson(const estimation::PipelineCounters& c) {
  io::Json j;
  j["scans_processed"] = c.scans_processed;
  j["scans_before_init"] = c.scans_before_init;
  j["scans_initializer"] = c.scans_initializer;
  j["scans_too_small"] = c.scans_too_small;
  j["scans_not_applied"] = c.scans_not_applied;
  j["scans_degenerate"] = c.scans_degenerate;
  j["scans_bad_health"] = c.scans_bad_health;
  j["points_dropped_sanitize"] = c.points_dropped_sanitize;
  j["queue"]["imu_duplicates"] = c.queue.imu_duplicates;
  j["queue"]["imu_stale"] = c.queue.imu_stale;
  j["queue"]["scan_duplicates"] = c.queue.scan_duplicates;
  j["queue"]["scan_stale"] = c.queue.scan_stale;
  j["queue"]["imu_gaps"] = c.queue.imu_gaps;
  j["queue"]["longest_imu_gap_s"] = NanosToSeconds(c.queue.longest_imu_gap_ns);
  return j;
}

RunResult RunLog(const RunRequest& request) {
  const config::RunConfig& config = request.config;
  std::filesystem::create_directories(request.out_dir);
  config::SaveRunConfig(request.out_dir + "/config.yaml", config);
  OdometryPipeline pipeline(config.PipelineOptions());

  // Prior map in a local frame near zero; everything written goes back to the world frame.
  const bool localizing = !request.prior_map.empty();
  mapping::PriorMap prior;
  if (localizing) {
    prior = LoadPriorMap(request.prior_map, config.prior_map, request.guess_world_imu, &pipeline);
  }
  const Eigen::Vector3d origin_world = prior.origin_world;

  auto log = io::OpenLog(request.log, config.LogOptions());
  std::vector<ScanResult> results;
  // Dense registered scans, one point per voxel (the crafting input and the c2c metric).
  // A hash of voxels, not a tree: nothing searches this map during the run, and the tree's
  // downsampling insert cost as much per scan as the odometry (hylo map, session A).
  const float dense_voxel_m = static_cast<float>(config.pipeline.output.dense_map_voxel_m);
  std::optional<registration::UniformSampler> dense_map;
  if (dense_voxel_m > 0.f) dense_map.emplace(dense_voxel_m);
  std::vector<estimation::NavState> finalized;
  std::size_t consumed = 0;
  auto consume = [&] {
    for (; consumed < results.size(); ++consumed) {
      auto& points = results[consumed].registered_points_map;
      if (dense_map && !points.empty()) dense_map->Add(points);
      PointCloud().swap(points);
    }
    for (estimation::NavState& x : pipeline.TakeFinalizedStates()) finalized.push_back(x);
  };
  io::Progress progress(request.label, 0, request.show_progress);
  io::LogMessage message;
  std::size_t scans = 0;
  while (log->Next(&message)) {
    if (message.kind == io::LogMessage::Kind::kImu) {
      pipeline.AddImu(message.imu);
      continue;
    }
    pipeline.AddScan(std::move(message.scan));
    pipeline.Process(&results);
    consume();
    progress.Update(++scans);
    if (pipeline.status() == OdometryPipeline::Status::kFailed) break;
  }
  pipeline.Finish(&results);
  consume();
  progress.Finish();
  if (pipeline.status() == OdometryPipeline::Status::kFailed) {
    throw std::runtime_error(request.log + ": " + pipeline.message());
  }
  if (results.empty()) throw std::runtime_error(request.log + ": no scan was processed");

  RunResult run;
  run.trajectory = WorldTrajectory(finalized, origin_world);
  run.live_trajectory = WorldTrajectory(LiveStates(results), origin_world);
  io::WriteTum(request.out_dir + "/trajectory.tum", run.trajectory);
  io::WriteTum(request.out_dir + "/trajectory_live.tum", run.live_trajectory);
  WriteOdometryCsv(request.out_dir + "/odometry.csv", results, origin_world, config.output);
  WriteTimingCsv(request.out_dir + "/timing.csv", results);
  WriteWorldCloud(request.out_dir + "/map.pcd", pipeline.map().Flatten(), origin_world);
  if (localizing && pipeline.map().run_size() > 0) {
    WriteWorldCloud(request.out_dir + "/map_added.pcd", pipeline.map().FlattenRun(), origin_world);
  }
  const PointCloud no_dense_map;
  const PointCloud& dense = dense_map ? dense_map->points() : no_dense_map;
  if (dense_map) WriteWorldCloud(request.out_dir + "/map_dense.pcd", dense, origin_world);

  double path_m = 0.0;
  std::vector<double> cpu_ms;
  for (const estimation::ScanResult& r : results) {
    run.ms_per_scan.push_back(r.total_ms);
    cpu_ms.push_back(r.cpu_ms);
  }
  for (std::size_t i = 1; i < finalized.size(); ++i) {
    path_m += (finalized[i].p_map_imu - finalized[i - 1].p_map_imu).norm();
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  io::Json& j = run.summary;
  j["log"] = request.log;
  j["mode"] = !localizing                                         ? "slam"
              : config.pipeline.localization.update_after_s < 0.0 ? "localization"
                                                                  : "hybrid";
  j["backend"] = config.BackendName();
  j["imu"] = config.pipeline.imu.enabled;
  j["scans_processed"] = results.size();
  j["counters"] = PipelineCountersJson(pipeline.counters());
  j["path_length_m"] = path_m;
  j["map_points"] = pipeline.map().Size();
  j["map_points_added"] = pipeline.map().run_size();
  j["ms_per_scan_median"] = Percentile(run.ms_per_scan, 0.5);
  j["ms_per_scan_p99"] = Percentile(run.ms_per_scan, 0.99);
  j["cpu_ms_per_scan_median"] = Percentile(cpu_ms, 0.5);
  j["cpu_ms_per_scan_p99"] = Percentile(cpu_ms, 0.99);
  j["peak_memory_mb"] = usage.ru_maxrss / 1024.0;
  j["elapsed_s"] = progress.ElapsedSeconds();
  j["origin_world"] = io::Json::array({origin_world.x(), origin_world.y(), origin_world.z()});
  j["events"] = EventsJson(pipeline.events(), origin_world);
  if (localizing) {
    j["prior_map"] = request.prior_map;
    j["prior_map_points"] = prior.num_kept;
    j["c2c"] = CloudToCloudJson(dense, prior.points_local, request.c2c_max_distance_m);
  }
  io::WriteJsonFile(request.out_dir + "/summary.json", j);
  return run;
}

}  // namespace hylo::run
