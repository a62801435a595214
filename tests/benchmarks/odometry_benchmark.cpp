// Odometry on simulated session A: accuracy against ground truth (ATE after SE(3) alignment,
// end drift) and per-scan time (median, p99, and per phase) and peak memory. The pipeline is
// single-threaded, so the times are one core's. After the run, the per-point price of plane
// association (k-nearest search + plane fit) is measured on the final map, next to nanoflann's
// search on the same points. Figures are printed and written as JSON, never asserted.
//
//   hylo_odometry_benchmark [--lidar vlp16|rs16] [--duration S] [--seed N] [--fast]
//                           [--scan-voxel M] [--point-stride N] [--json PATH]
// --fast uses the simulator's coarse settings (1 deg columns) as the CI test does.

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <string>

#include "benchmark_common.h"
#include "estimation/sim_odometry_util.h"
#include "hylo/registration/plane_matcher.h"
#include "nanoflann_tree.h"

namespace {

// The per-point price of plane association on the run's final map: queries are map points
// moved by up to half a map voxel on each axis (like fresh scan points on mapped surfaces).
// nanoflann answers the same k-nearest queries on a static tree over the same points, as a
// yardstick of what an exact search costs on this machine.
struct AssociationCost {
  std::size_t queries = 0;
  double knn_us = 0.0;            // one k-nearest search on the map, us of thread CPU
  double match_us = 0.0;          // the search plus the plane fit (PlaneMatcher::Match)
  double nanoflann_knn_us = 0.0;  // the same search with nanoflann
  double matched_fraction = 0.0;  // queries that found a plane
};

AssociationCost MeasureAssociation(const hylo::mapping::MapManager& map,
                                   const hylo::odometry::OdometryPipelineOptions& options) {
  using hylo::PointCloud;
  AssociationCost cost;
  const PointCloud points = map.Flatten();
  if (points.empty()) return cost;
  std::mt19937 rng(7);
  const float half = static_cast<float>(0.5 * options.map.voxel_size_m);
  std::uniform_real_distribution<float> jitter(-half, half);
  std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
  PointCloud queries(20000);
  for (Eigen::Vector3f& q : queries) {
    q = points[pick(rng)] + Eigen::Vector3f(jitter(rng), jitter(rng), jitter(rng));
  }
  const int k = options.planes.num_neighbors;
  const auto max_distance = static_cast<float>(options.planes.max_neighbor_distance_m);
  const double n = static_cast<double>(queries.size());
  std::vector<hylo::registration::Neighbor> neighbors;
  using hylo::benchmarks::NowMs;  // thread CPU time, ms
  double start_ms = NowMs();
  for (const Eigen::Vector3f& q : queries) map.KNearest(q, k, max_distance, &neighbors);
  cost.knn_us = 1e3 * (NowMs() - start_ms) / n;

  const hylo::registration::PlaneMatcher matcher(map, options.planes);
  hylo::registration::Plane plane;
  std::size_t matched = 0;
  start_ms = NowMs();
  for (const Eigen::Vector3f& q : queries) matched += matcher.Match(q.cast<double>(), &plane);
  cost.match_us = 1e3 * (NowMs() - start_ms) / n;
  cost.matched_fraction = matched / n;

  hylo::benchmarks::NanoflannTree nanoflann;
  nanoflann.Build(points);
  std::vector<float> d2;
  start_ms = NowMs();
  for (const Eigen::Vector3f& q : queries) nanoflann.KNearest(q, k, &d2);
  cost.nanoflann_knn_us = 1e3 * (NowMs() - start_ms) / n;
  cost.queries = queries.size();
  return cost;
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
}

}  // namespace

int main(int argc, char** argv) {
  using namespace hylo;  // NOLINT
  std::string lidar = "vlp16", json_path, trace_path;
  double duration_s = 120.0;
  uint64_t seed = 5;
  bool fast = false, no_deskew = false, imu_noise_free = false;
  // Settings to explore (defaults = the library's defaults).
  double accel_bias_sigma = -1.0, lidar_noise = -1.0, rotation_sigma = -1.0, gravity_sigma = -1.0, scan_voxel = -1.0, map_voxel = -1.0;
  int iterations = -1, point_stride = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--lidar" && has_value) {
      lidar = argv[++i];
    } else if (a == "--duration" && has_value) {
      duration_s = std::atof(argv[++i]);
    } else if (a == "--seed" && has_value) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (a == "--json" && has_value) {
      json_path = argv[++i];
    } else if (a == "--accel-bias-sigma" && has_value) {
      accel_bias_sigma = std::atof(argv[++i]);
    } else if (a == "--lidar-noise" && has_value) {
      lidar_noise = std::atof(argv[++i]);
    } else if (a == "--rotation-sigma" && has_value) {
      rotation_sigma = std::atof(argv[++i]);
    } else if (a == "--gravity-sigma" && has_value) {
      gravity_sigma = std::atof(argv[++i]);
    } else if (a == "--scan-voxel" && has_value) {
      scan_voxel = std::atof(argv[++i]);
    } else if (a == "--map-voxel" && has_value) {
      map_voxel = std::atof(argv[++i]);
    } else if (a == "--point-stride" && has_value) {
      point_stride = std::atoi(argv[++i]);
    } else if (a == "--iterations" && has_value) {
      iterations = std::atoi(argv[++i]);
    } else if (a == "--trace" && has_value) {
      trace_path = argv[++i];
    } else if (a == "--no-deskew") {
      no_deskew = true;
    } else if (a == "--imu-noise-free") {
      imu_noise_free = true;
    } else if (a == "--fast") {
      fast = true;
    } else {
      std::fprintf(stderr, "unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  sim::SimulationOptions sim_options =
      fast ? sim::SimulationOptions::Fast(duration_s) : sim::SimulationOptions{};
  sim_options.duration_a_s = duration_s;
  sim_options.seed = seed;
  if (!sim::ParseLidarModel(lidar, &sim_options.lidar.model)) {
    std::fprintf(stderr, "unknown lidar '%s'\n", lidar.c_str());
    return 2;
  }
  if (imu_noise_free) sim_options.imu = sim_options.imu.NoiseFree();
  odometry::OdometryPipelineOptions options = testing::PipelineOptionsFor(sim_options);
  if (no_deskew) options.preprocess.deskew = false;
  if (accel_bias_sigma > 0) {
    options.initial_uncertainty.accel_bias_sigma_mps2 = accel_bias_sigma;
  }
  if (lidar_noise > 0) options.estimator.lidar_update.lidar_noise_m = lidar_noise;
  if (rotation_sigma > 0) options.initial_uncertainty.rotation_sigma_rad = rotation_sigma;
  if (gravity_sigma > 0) options.initial_uncertainty.gravity_sigma_mps2 = gravity_sigma;
  if (scan_voxel >= 0) options.preprocess.scan_voxel_m = scan_voxel;
  if (map_voxel > 0) options.map.voxel_size_m = map_voxel;
  if (point_stride > 0) options.preprocess.point_stride = point_stride;
  if (iterations > 0) options.estimator.ieskf.max_iterations = iterations;
  const auto start = std::chrono::steady_clock::now();
  const sim::Site site = sim::BuildSite(sim_options.seed, sim_options.terrain);
  const sim::SessionSimulator simulator(sim_options, site, sim::SessionId::kA);
  testing::PipelineSink sink(options);
  simulator.Run(&sink);
  const testing::SimRun run = sink.Finish();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (run.failed) {
    std::fprintf(stderr, "pipeline failed: %s\n", run.message.c_str());
    return 1;
  }
  std::vector<double> total, update, cpu, preprocess, map_update, update_iterations;
  double points = 0.0, matches = 0.0;
  std::size_t degenerate = 0, not_applied = 0;
  for (const auto& r : run.results) {
    total.push_back(r.total_ms);
    cpu.push_back(r.cpu_ms);
    update.push_back(r.update_ms);
    preprocess.push_back(r.deskew_ms);
    map_update.push_back(r.map_ms);
    update_iterations.push_back(r.update.iterations);
    points += r.downsampled_points;
    matches += r.update.num_matches;
    degenerate += r.update.degenerate ? 1 : 0;
    not_applied += r.update.applied ? 0 : 1;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double peak_mb = usage.ru_maxrss / 1024.0;
  const auto& ate = run.ate;
  const double end_error_aligned_m =
      ate.translation_errors_m.empty() ? 0.0 : ate.translation_errors_m.back();
  std::printf("session A, %s%s, seed %llu, %.0f s: %zu scans, %.0f points/scan after "
              "downsampling, path %.1f m\n",
              lidar.c_str(), fast ? " (fast sim)" : "", static_cast<unsigned long long>(seed),
              duration_s, run.results.size(), points / std::max<std::size_t>(1, total.size()),
              ate.path_length_m);
  std::printf("  ATE RMSE %.4f m (max %.4f m), rotation RMSE %.3f deg\n", ate.rmse_m, ate.max_m,
              ate.rotation_rmse_deg);
  std::printf("  end drift %.4f m = %.3f %% of distance (aligned at the first pose); end error "
              "after SE(3) alignment %.4f m = %.3f %%\n",
              ate.end_drift_m, ate.end_drift_percent, end_error_aligned_m,
              100.0 * end_error_aligned_m / std::max(1e-9, ate.path_length_m));
  std::printf("  per scan: median %.2f ms, p99 %.2f ms, max %.2f ms\n", Percentile(total, 0.5),
              Percentile(total, 0.99), Percentile(total, 1.0));
  std::printf("  per scan CPU time: median %.2f ms, p99 %.2f ms, max %.2f ms\n",
              Percentile(cpu, 0.5), Percentile(cpu, 0.99), Percentile(cpu, 1.0));
  std::printf("  per scan medians: clean-up + downsampling + undistortion %.2f ms, update %.2f ms "
              "(%.0f iterations, %.0f %% of points matched to planes), map insertion %.2f ms\n",
              Percentile(preprocess, 0.5), Percentile(update, 0.5),
              Percentile(update_iterations, 0.5), 100.0 * matches / std::max(1.0, points),
              Percentile(map_update, 0.5));
  std::printf("  scans degenerate %zu, not applied %zu; map %zu points; peak memory %.0f MB "
              "(simulator included); wall %.1f s (simulation included)\n",
              degenerate, not_applied, run.map_points, peak_mb, wall_s);
  const AssociationCost association = MeasureAssociation(sink.pipeline().map(), options);
  const double points_per_scan = points / std::max<std::size_t>(1, total.size());
  std::printf("  plane association on the final map (%zu queries, %.0f %% find a plane): "
              "%d-NN search %.2f us (nanoflann %.2f us), with the plane fit %.2f us per point "
              "= %.2f ms for %.0f points\n",
              association.queries, 100.0 * association.matched_fraction,
              options.planes.num_neighbors, association.knn_us, association.nanoflann_knn_us,
              association.match_us, association.match_us * points_per_scan * 1e-3,
              points_per_scan);
  if (!trace_path.empty()) {  // t, estimated and true pose (x y z qx qy qz qw) per scan
    std::ofstream out(trace_path);
    out.precision(9);
    for (const auto& e : run.estimate) {
      Eigen::Isometry3d truth;
      if (!evaluation::InterpolatePose(run.reference, e.t_ns, &truth)) continue;
      const Eigen::Quaterniond qe(e.T_world_body.linear()), qt(truth.linear());
      out << e.t_ns * 1e-9 << ' ' << e.T_world_body.translation().transpose() << ' '
          << qe.coeffs().transpose() << ' ' << truth.translation().transpose() << ' '
          << qt.coeffs().transpose() << '\n';
    }
  }
  if (!json_path.empty()) {
    std::ofstream out(json_path);
    out << "{\"lidar\": \"" << lidar << "\", \"duration_s\": " << duration_s
        << ", \"scans\": " << run.results.size() << ", \"path_length_m\": " << ate.path_length_m
        << ", \"ate_rmse_m\": " << ate.rmse_m << ", \"end_drift_percent\": "
        << ate.end_drift_percent << ", \"ms_median\": " << Percentile(total, 0.5)
        << ", \"ms_p99\": " << Percentile(total, 0.99) << ", \"cpu_ms_median\": "
        << Percentile(cpu, 0.5) << ", \"cpu_ms_p99\": " << Percentile(cpu, 0.99)
        << ", \"peak_memory_mb\": " << peak_mb << ", \"update_ms_median\": "
        << Percentile(update, 0.5) << ", \"knn_us\": " << association.knn_us
        << ", \"nanoflann_knn_us\": " << association.nanoflann_knn_us
        << ", \"plane_match_us\": " << association.match_us
        << "}\n";
  }
  return 0;
}
