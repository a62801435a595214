#include "hylo/run/run_log.h"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/common/time.h"
#include "hylo/config/config_json.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/evaluation/cloud_distance.h"
#include "hylo/io/cloud_io.h"
#include "hylo/logs/log_reader.h"
#include "hylo/io/progress.h"
#include "hylo/registration/voxel_filter.h"
#include "hylo/run/prior_map_io.h"
#include "hylo/run/session.h"
#include "hylo/tiles/tiled_prior_map.h"
#include "run_outputs.h"

namespace hylo::run {
namespace {

using odometry::OdometryPipeline;
using odometry::ScanResult;

io::Json EventsJson(const std::vector<localization::LocalizationEvent>& events,
                    const Eigen::Vector3d& origin_world) {
  io::Json array = io::Json::array();
  for (const auto& e : events) {
    io::Json j;
    j["kind"] = localization::ToString(e.kind);
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
io::Json CloudToCloudJson(const PointCloud& registered_map,
                          const registration::NeighborSearch& reference, double max_distance_m) {
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

// The run's files but summary.json (run_log.h); returns the points written as added tiles.
std::size_t WriteRunFiles(const RunRequest& request, const Session& session,
                          const RunResult& run) {
  const std::string& dir = request.out_dir;
  const OdometryPipeline& pipeline = session.pipeline();
  const mapping::PriorMap& prior = session.prior();
  const Eigen::Vector3d& origin_world = session.origin_world();
  io::WriteTum(dir + "/trajectory.tum", run.trajectory);
  io::WriteTum(dir + "/trajectory_live.tum", run.live_trajectory);
  // Poses that are not a place in the map have a file of their own (odometry.csv's
  // pose_status says which is which); written only when there are some.
  const std::vector<io::StampedPose> provisional = session.ProvisionalTrajectory();
  if (!provisional.empty()) io::WriteTum(dir + "/trajectory_provisional.tum", provisional);
  WriteOdometryCsv(dir + "/odometry.csv", session.results(), origin_world, request.config.output);
  WriteTimingCsv(dir + "/timing.csv", session.results());
  // A tiled prior is never whole in memory: its run writes only what it added, as tiles.
  const bool tiled = !prior.tiled_dir.empty();
  const bool added = pipeline.map().run_size() > 0 || !pipeline.map().windowed_out().empty();
  if (!tiled) WriteWorldCloud(dir + "/map.pcd", pipeline.map().Flatten(), origin_world);
  if (session.localizing() && !tiled && pipeline.map().run_size() > 0) {
    WriteWorldCloud(dir + "/map_added.pcd", pipeline.map().FlattenRun(), origin_world);
  }
  std::size_t tiles_added = 0;
  if (tiled && added) {
    tiles_added = tiles::WriteAddedTiles(dir + "/map_added", prior, pipeline,
                                         request.config.pipeline.map.voxel_size_m);
  }
  if (request.config.pipeline.output.dense_map_voxel_m > 0.0) {
    WriteWorldCloud(dir + "/map_dense.pcd", session.dense_map(), origin_world);
  }
  return tiles_added;
}

}  // namespace

io::Json OnlineCalibrationJson(const estimation::OnlineCalibration& c,
                               double configured_time_offset_s) {
  constexpr double kDegPerRad = 180.0 / M_PI;
  io::Json j;
  if (c.time_offset_estimated) {
    j["time_offset_correction_s"] = c.time_offset_correction_s;
    j["time_offset_sigma_s"] = c.time_offset_sigma_s;
    j["lidar_time_offset_s"] = configured_time_offset_s + c.time_offset_correction_s;
  }
  if (c.extrinsic_rotation_estimated) {
    const Eigen::Vector3d& r = c.extrinsic_rotation_correction_rad;
    const Eigen::Vector3d& s = c.extrinsic_rotation_sigma_rad;
    j["extrinsic_rotation_correction_deg"] =
        io::Json::array({r.x() * kDegPerRad, r.y() * kDegPerRad, r.z() * kDegPerRad});
    j["extrinsic_rotation_sigma_deg"] =
        io::Json::array({s.x() * kDegPerRad, s.y() * kDegPerRad, s.z() * kDegPerRad});
  }
  if (c.extrinsic_translation_estimated) {
    const Eigen::Vector3d& t = c.extrinsic_translation_correction_m;
    const Eigen::Vector3d& s = c.extrinsic_translation_sigma_m;
    j["extrinsic_translation_correction_m"] = io::Json::array({t.x(), t.y(), t.z()});
    j["extrinsic_translation_sigma_m"] = io::Json::array({s.x(), s.y(), s.z()});
  }
  return j;
}

namespace {

// "[a, b, c] unit (sigma [d, e, f])" of a summary's vector and its sigmas, at `decimals`.
std::string VectorWithSigma(const io::Json& values, const io::Json& sigmas, const char* unit,
                            int decimals) {
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), "[%.*f, %.*f, %.*f] %s (sigma [%.*f, %.*f, %.*f])",
                decimals, values.at(0).get<double>(), decimals, values.at(1).get<double>(),
                decimals, values.at(2).get<double>(), unit, decimals, sigmas.at(0).get<double>(),
                decimals, sigmas.at(1).get<double>(), decimals, sigmas.at(2).get<double>());
  return buffer;
}

}  // namespace

std::string OnlineCalibrationLine(const io::Json& summary) {
  if (!summary.contains("online_calibration")) return "";
  const io::Json& c = summary.at("online_calibration");
  std::vector<std::string> parts;
  if (c.contains("lidar_time_offset_s")) {
    char buffer[160];
    std::snprintf(buffer, sizeof(buffer),
                  "lidar.time_offset_s %.4f s (correction %+.1f ms, sigma %.1f ms)",
                  c.at("lidar_time_offset_s").get<double>(),
                  1e3 * c.at("time_offset_correction_s").get<double>(),
                  1e3 * c.at("time_offset_sigma_s").get<double>());
    parts.push_back(buffer);
  }
  if (c.contains("extrinsic_rotation_correction_deg")) {
    parts.push_back("extrinsic rotation correction " +
                    VectorWithSigma(c.at("extrinsic_rotation_correction_deg"),
                                    c.at("extrinsic_rotation_sigma_deg"), "deg", 2));
  }
  if (c.contains("extrinsic_translation_correction_m")) {
    parts.push_back("extrinsic translation correction " +
                    VectorWithSigma(c.at("extrinsic_translation_correction_m"),
                                    c.at("extrinsic_translation_sigma_m"), "m", 3));
  }
  std::string line = "online calibration (sigma from the estimator, optimistic):";
  for (std::size_t i = 0; i < parts.size(); ++i) line += (i == 0 ? " " : "; ") + parts[i];
  return line;
}

io::Json PipelineCountersJson(const odometry::PipelineCounters& c) {
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
  j["queue"]["imu_non_finite"] = c.queue.imu_non_finite;
  j["queue"]["imu_saturated"] = c.queue.imu_saturated;
  j["queue"]["imu_gaps"] = c.queue.imu_gaps;
  j["queue"]["longest_imu_gap_s"] = NanosToSeconds(c.queue.longest_imu_gap_ns);
  j["queue"]["imu_gap_total_s"] = NanosToSeconds(c.queue.imu_gap_total_ns);
  j["queue"]["scans_past_imu"] = c.queue.scans_past_imu;
  return j;
}

io::Json LogRecoveryJson(const logs::LogRecovery& r) {
  io::Json j;
  j["damage"] = r.damage;
  j["stop_reason"] = r.stop_reason;
  j["messages_recovered"] = r.messages;
  j["span_s"] = r.messages > 0 ? r.span_s() : 0.0;
  j["file_bytes"] = r.file_bytes;
  j["unreadable_bytes"] = r.unreadable_bytes;
  j["summary"] = r.Summary();
  return j;
}

std::string ImuFaultsLine(const odometry::QueueCounters& q, std::size_t unread_non_finite) {
  std::string line;
  const auto add = [&](std::size_t n, const std::string& what) {
    if (n > 0) line += (line.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  };
  if (q.imu_gaps > 0) {
    char gaps[96];
    std::snprintf(gaps, sizeof(gaps), "gap%s (longest %.3f s, %.3f s in all)",
                  q.imu_gaps == 1 ? "" : "s", NanosToSeconds(q.longest_imu_gap_ns),
                  NanosToSeconds(q.imu_gap_total_ns));
    add(q.imu_gaps, gaps);
  }
  add(q.imu_duplicates, "duplicated stamps dropped");
  add(q.imu_stale, "stamps going backwards dropped");
  add(q.imu_non_finite + unread_non_finite, "NaN/inf samples dropped");
  add(q.imu_saturated, "clipped (full-scale) samples dropped");
  add(q.scans_past_imu, "scans registered while the IMU was silent");
  return line;
}

RunResult RunLog(const RunRequest& request) {
  const config::RunConfig& config = request.config;
  const bool write = !request.out_dir.empty();
  if (write) {
    std::error_code ec;
    std::filesystem::create_directories(request.out_dir, ec);
    if (ec) {
      throw std::runtime_error("cannot create the output folder '" + request.out_dir +
                               "': " + ec.message());
    }
    config::SaveRunConfig(request.out_dir + "/config.yaml", config);
  }
  Session session(config.PipelineOptions());
  const OdometryPipeline& pipeline = session.pipeline();

  // Prior map in a local frame near zero; everything written goes back to the world frame.
  const bool localizing = !request.prior_map.empty();
  if (localizing) {
    session.LoadPriorMap(request.prior_map, config.prior_map, request.guess_world_imu);
  }
  const mapping::PriorMap& prior = session.prior();
  const Eigen::Vector3d origin_world = session.origin_world();
  const double prior_loaded_after_s = session.ElapsedSeconds();

  auto log = logs::OpenLog(request.log, config.LogOptions());
  if (const logs::LogRecovery* r = log->recovery()) {
    std::fprintf(stderr, "warning: %s: %s: read record by record up to its last complete message\n",
                 request.log.c_str(), r->damage.c_str());
  }
  io::Progress progress(request.label, 0, request.show_progress);
  logs::LogMessage message;
  while (log->Next(&message)) {
    if (message.kind == logs::LogMessage::Kind::kImu) {
      session.AddImu(message.imu);
      continue;
    }
    session.AddScan(std::move(message.scan));
    progress.Update(session.scans_added());
    if (request.on_scan) request.on_scan(session.scans_added());
    if (session.failed()) break;
  }
  session.Finish();
  progress.Finish();
  const logs::LogRecovery* recovery = log->recovery();
  if (recovery != nullptr) {
    std::fprintf(stderr, "warning: %s: %s\n", request.log.c_str(), recovery->Summary().c_str());
  }
  const std::string imu_faults =
      ImuFaultsLine(pipeline.counters().queue, log->counters().dropped_non_finite_imu);
  if (!imu_faults.empty()) {
    std::fprintf(stderr, "warning: %s: IMU: %s\n", request.log.c_str(), imu_faults.c_str());
  }
  if (session.failed()) throw RunFailed(request.log + ": " + pipeline.message());
  const std::vector<ScanResult>& results = session.results();
  if (results.empty()) throw RunFailed(request.log + ": no scan was processed");

  RunResult run;
  run.trajectory = session.Trajectory();
  run.live_trajectory = session.LiveTrajectory();
  const bool tiled = !prior.tiled_dir.empty();
  const std::size_t tiles_added = write ? WriteRunFiles(request, session, run) : 0;
  const PointCloud& dense = session.dense_map();
  const std::vector<estimation::NavState>& finalized = session.finalized();

  double path_m = 0.0;
  std::vector<double> cpu_ms;
  for (const odometry::ScanResult& r : results) {
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
  std::size_t by_status[3] = {0, 0, 0};
  for (const ScanResult& r : results) ++by_status[static_cast<int>(r.pose_status)];
  j["scans_by_pose_status"] = {{"valid", by_status[0]}, {"lost", by_status[1]},
                               {"provisional", by_status[2]}};
  j["counters"] = PipelineCountersJson(pipeline.counters());
  const estimation::OnlineCalibration calibration = pipeline.estimator().Calibration();
  if (calibration.time_offset_estimated || calibration.extrinsic_rotation_estimated ||
      calibration.extrinsic_translation_estimated) {
    j["online_calibration"] =
        OnlineCalibrationJson(calibration, config.pipeline.lidar.time_offset_s);
  }
  const logs::LogReadCounters& read = log->counters();
  j["log_read"]["imu_messages"] = read.imu_messages;
  j["log_read"]["scan_messages"] = read.scan_messages;
  j["log_read"]["dropped_non_finite_points"] = read.dropped_non_finite_points;
  j["log_read"]["dropped_non_finite_imu"] = read.dropped_non_finite_imu;
  j["log_read"]["empty_scans"] = read.empty_scans;
  j["log_read"]["recovery"] = recovery != nullptr ? LogRecoveryJson(*recovery) : io::Json();
  j["path_length_m"] = path_m;
  j["map_points"] = pipeline.map().Size();
  j["map_points_added"] = pipeline.map().run_size();
  j["ms_per_scan_median"] = Percentile(run.ms_per_scan, 0.5);
  j["ms_per_scan_p99"] = Percentile(run.ms_per_scan, 0.99);
  j["cpu_ms_per_scan_median"] = Percentile(cpu_ms, 0.5);
  j["cpu_ms_per_scan_p99"] = Percentile(cpu_ms, 0.99);
  j["peak_memory_mb"] = usage.ru_maxrss / 1024.0;
  j["elapsed_s"] = progress.ElapsedSeconds();
  j["prior_map_loaded_after_s"] = prior_loaded_after_s;
  j["first_pose_after_s"] = session.first_pose_after_s();
  j["first_pose_cpu_s"] = session.first_pose_cpu_s();
  j["origin_world"] = io::Json::array({origin_world.x(), origin_world.y(), origin_world.z()});
  j["events"] = EventsJson(pipeline.events(), origin_world);
  if (localizing) {
    j["prior_map"] = request.prior_map;
    j["prior_map_points"] = prior.num_kept;
    if (tiled) {
      j["prior_map_tiles"] = tiles::TiledPriorJson(pipeline);
      j["prior_map_tiles"]["added_points_written"] = tiles_added;
    }
    const auto reference =
        PriorSearch(prior, pipeline,
                    static_cast<std::size_t>(config.prior_map.tile_cache_million_points * 1e6));
    j["c2c"] = CloudToCloudJson(dense, *reference, request.c2c_max_distance_m);
  }
  // The effective configuration beside the figures it produced (config.yaml holds the same).
  j["config"] = config::ToJson(config);
  if (write) io::WriteJsonFile(request.out_dir + "/summary.json", j);
  return run;
}

}  // namespace hylo::run
