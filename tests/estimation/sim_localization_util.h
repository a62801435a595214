#pragma once
// Localization on the simulator: a prior map built by SLAM on session A (dense registered
// scans, as `hylo map` writes map_dense.pcd), then session B streamed into a localizing
// pipeline. Everything stays in memory; each run re-simulates its session (memory stays flat).

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "estimation/sim_odometry_util.h"
#include "hylo/registration/voxel_filter.h"
#include "hylo/sim/site_layout.h"

namespace hylo::testing {

/// Streams a session into a session of the pipeline (configured by the caller, e.g. with a
/// prior map), which folds each result's registered scan into its dense map.
class LocalizationSink : public sim::SessionSink {
 public:
  explicit LocalizationSink(const odometry::OdometryPipelineOptions& options)
      : session(options), pipeline(session.pipeline()) {}

  void OnImu(const ImuSample& s) override { session.AddImu(s); }
  void OnScan(const LidarScan& s) override {
    if (before_scan) before_scan(scans_seen_, &pipeline);
    ++scans_seen_;
    session.AddScan(s);
  }
  void OnTruth(const sim::TruthSample& t) override { truth.push_back({t.t_ns, t.T_map_imu}); }
  void Finish() { session.Finish(); }

  /// T_map_imu per processed scan, finalized (the trajectory a run writes).
  std::vector<evaluation::TimedPose> Estimate() const {
    std::vector<evaluation::TimedPose> estimate;
    for (const auto& x : session.finalized()) {
      estimate.push_back({x.t_ns, Eigen::Isometry3d(x.T_map_imu().Matrix())});
    }
    return estimate;
  }
  /// T_map_imu per scan placed in the map, live (the odometry stream).
  std::vector<evaluation::TimedPose> LiveEstimate() const {
    std::vector<evaluation::TimedPose> estimate;
    for (const auto& r : results()) {
      estimate.push_back({r.t_ns, Eigen::Isometry3d(r.state.T_map_imu().Matrix())});
    }
    return estimate;
  }
  /// The results whose pose is a place in the map (not those of a search or of a lost vehicle).
  std::vector<odometry::ScanResult> results() const {
    std::vector<odometry::ScanResult> valid;
    for (const auto& r : session.results()) {
      if (r.pose_status == odometry::PoseStatus::kValid) valid.push_back(r);
    }
    return valid;
  }
  /// Every scan's result, provisional and lost ones included.
  const std::vector<odometry::ScanResult>& all_results() const { return session.results(); }

  run::Session session;
  odometry::OdometryPipeline& pipeline;       // session's
  std::vector<evaluation::TimedPose> truth;  // T_site_imu at the IMU rate
  /// Called before the scan with this index enters the pipeline (e.g. a relocalization).
  std::function<void(std::size_t, odometry::OdometryPipeline*)> before_scan;

 private:
  std::size_t scans_seen_ = 0;
};

/// Session A mapped by SLAM: the dense map in A's map frame and where that frame lies on the
/// site (from A's first pose against the truth).
struct SimPrior {
  PointCloud points_map;
  Eigen::Isometry3d T_site_map = Eigen::Isometry3d::Identity();
  evaluation::AteResult slam_ate;
};

inline SimPrior BuildSimPrior(const sim::SimulationOptions& sim_options, const sim::Site& site) {
  odometry::OdometryPipelineOptions options = PipelineOptionsFor(sim_options);
  options.output.dense_map_voxel_m = 0.1;
  LocalizationSink sink(options);
  sim::SessionSimulator(sim_options, site, sim::SessionId::kA).Run(&sink);
  sink.Finish();
  SimPrior prior;
  prior.points_map = sink.session.dense_map();
  const std::vector<evaluation::TimedPose> estimate = sink.Estimate();
  if (estimate.empty()) return prior;
  // The map's place on the site fitted over the whole run, not read off the first pose: a
  // start attitude off by a fraction of a degree would tilt the whole map by it, and tests
  // that compare absolute poses (global localization) would measure that tilt, not themselves.
  const evaluation::AssociatedPoses pairs = evaluation::Associate(estimate, sink.truth);
  const evaluation::AlignmentResult fit =
      evaluation::AlignTrajectories(pairs.estimate, pairs.reference, evaluation::Alignment::kSE3);
  Eigen::Isometry3d T_site_imu;
  if (fit.ok) {
    prior.T_site_map = fit.T_reference_estimate;
  } else if (evaluation::InterpolatePose(sink.truth, estimate.front().t_ns, &T_site_imu)) {
    prior.T_site_map = T_site_imu * estimate.front().T_world_body.inverse();
  }
  prior.slam_ate = evaluation::ComputeAte(estimate, sink.truth);
  return prior;
}

/// BuildSimPrior through a file cache in `cache_path`: ctest runs every test case in its own
/// process, and SLAM on session A (~40 s of CPU) should run once per build, not per case.
/// An exclusive lock makes concurrent cases wait for the first one instead of repeating it.
inline SimPrior CachedSimPrior(const sim::SimulationOptions& sim_options, const sim::Site& site,
                               const std::string& cache_path) {
  const int lock = ::open((cache_path + ".lock").c_str(), O_CREAT | O_RDWR, 0644);
  if (lock >= 0) ::flock(lock, LOCK_EX);
  SimPrior prior;
  std::ifstream in(cache_path, std::ios::binary);
  uint64_t n = 0;
  if (in && in.read(reinterpret_cast<char*>(&n), sizeof(n))) {
    prior.points_map.resize(n);
    in.read(reinterpret_cast<char*>(prior.T_site_map.matrix().data()), 16 * sizeof(double));
    in.read(reinterpret_cast<char*>(&prior.slam_ate.rmse_m), sizeof(double));
    in.read(reinterpret_cast<char*>(prior.points_map.data()), n * sizeof(Eigen::Vector3f));
    if (!in) prior = SimPrior();
  }
  if (prior.points_map.empty()) {
    prior = BuildSimPrior(sim_options, site);
    const std::string tmp = cache_path + ".tmp";
    std::ofstream out(tmp, std::ios::binary);
    n = prior.points_map.size();
    out.write(reinterpret_cast<const char*>(&n), sizeof(n));
    out.write(reinterpret_cast<const char*>(prior.T_site_map.matrix().data()), 16 * sizeof(double));
    out.write(reinterpret_cast<const char*>(&prior.slam_ate.rmse_m), sizeof(double));
    out.write(reinterpret_cast<const char*>(prior.points_map.data()), n * sizeof(Eigen::Vector3f));
    out.close();
    if (out) std::rename(tmp.c_str(), cache_path.c_str());
  }
  if (lock >= 0) ::close(lock);  // releases the lock
  return prior;
}

/// CachedSimPrior keyed by what determines the prior: `name` (the options it was built with)
/// and this build of the executable (a rebuilt library relinks it, so a changed pipeline never
/// meets a stale prior). The file lies next to the executable, as `<name>_<mtime>.bin`; the
/// caches of earlier builds under the same name (~14 MB each) are removed.
inline SimPrior CachedSimPriorForThisBuild(const sim::SimulationOptions& sim_options,
                                           const sim::Site& site, const std::string& name) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  const fs::path dir = error ? fs::current_path() : exe.parent_path();
  const std::string stamp =
      error ? std::string("0")
            : std::to_string(fs::last_write_time(exe, error).time_since_epoch().count());
  const std::string current = name + "_" + stamp + ".bin";
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, error)) {
    const std::string file = entry.path().filename().string();
    const bool same_name = file.rfind(name + "_", 0) == 0;
    const std::string rest = same_name ? file.substr(name.size() + 1) : std::string();
    const std::size_t digits = rest.find_first_not_of("0123456789");
    const bool earlier = digits != std::string::npos && digits > 0 &&
                         (rest.substr(digits) == ".bin" || rest.substr(digits) == ".bin.lock") &&
                         rest.compare(0, digits, stamp) != 0;
    if (earlier) fs::remove(entry.path(), error);
  }
  return CachedSimPrior(sim_options, site, (dir / current).string());
}

}  // namespace hylo::testing
