// An hour on the simulated substation, in memory: session B's changed site driven round the
// lanes' outer loop (x = 22..93, y = 12..63) for the whole session, localized in the SLAM map of
// session A, once in localization-only and once in hybrid mode. The scans stream from the
// simulator straight into the pipeline (nothing is recorded: an hour of scans would be ~36 GB)
// and every result is dropped once read, so what the process holds is what the pipeline holds.
//
// Every 10 s of session time the resident set (VmRSS of /proc/self/status) is sampled; every
// minute one line: RSS, map points (prior + added), points added and the area they cover (1 m
// cells: every cell touched by added points, and the cells without a prior point), the ATE of
// that minute. At the end: the ATE over the hour (absolute, in the site frame: no alignment)
// and the RSS growth after minute 5.
//
//   hylo_hour_benchmark [--minutes M] [--mode localization|hybrid|both]
//                       [--backend ieskf|sliding_window] [--column-deg D] [--json PATH]
//
// Figures are printed and written as JSON, never asserted. Run it with `nice`: an hour of
// simulation and odometry takes CPU time of the order of the session per mode.

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <string>
#include <unordered_set>
#include <vector>

#include "benchmark_common.h"
#include "estimation/sim_localization_util.h"
#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/run/session.h"

namespace {

using hylo::odometry::OdometryPipeline;

/// VmRSS of this process, MB.
double RssMb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
  }
  return 0.0;
}

double ProcessCpuS() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// A 1 m xy cell.
int64_t Cell(const Eigen::Vector3f& p) {
  const auto x = static_cast<int64_t>(std::floor(p.x())),
             y = static_cast<int64_t>(std::floor(p.y()));
  return (x + (int64_t{1} << 30)) << 32 | (y + (int64_t{1} << 30));
}

/// The outer loop of the lanes, `laps` times, starting and ending at its south-west corner.
std::vector<Eigen::Vector2d> LoopRoute(int laps) {
  const std::vector<Eigen::Vector2d> corners = {{22, 12}, {93, 12}, {93, 63}, {22, 63}};
  std::vector<Eigen::Vector2d> route;
  for (int lap = 0; lap < laps; ++lap) route.insert(route.end(), corners.begin(), corners.end());
  route.push_back(corners.front());
  return route;
}

struct Minute {
  double rss_mb = 0.0;
  double map_mb = 0.0;  // the map's own accounting (MapManager::MemoryBytes)
  std::size_t map_points = 0, added_points = 0;
  double touched_m2 = 0.0, outside_prior_m2 = 0.0;
  double ate_m = 0.0;  // RMSE of the minute's finalized states
  double cpu_s = 0.0;
};

class HourSink : public hylo::sim::SessionSink {
 public:
  HourSink(const hylo::odometry::OdometryPipelineOptions& options,
           const Eigen::Isometry3d& T_site_map, const std::unordered_set<int64_t>& prior_cells,
           bool hybrid)
      : session(options, hylo::run::SessionKeeps{false, false, false}),
        pipeline(session.pipeline()),
        T_site_map_(T_site_map),
        prior_cells_(prior_cells),
        hybrid_(hybrid) {
    session.OnResult([this](const hylo::odometry::ScanResult& r) { CountAdded(r); });
    session.OnFinalized([this](const hylo::estimation::NavState& x) { Score(x); });
  }

  void OnImu(const hylo::ImuSample& s) override { session.AddImu(s); }
  void OnTruth(const hylo::sim::TruthSample& t) override {
    truth_.push_back({t.t_ns, t.T_map_imu});
    while (truth_.size() > 1000) truth_.pop_front();  // 5 s: more than any back-end's lag
  }
  void OnScan(const hylo::LidarScan& s) override {
    if (t0_ < 0) t0_ = s.t_ns;
    session.AddScan(s);
    const int64_t since = s.t_ns - t0_;
    while (since >= next_sample_ns_) {  // every 10 s of session time
      rss_samples_.push_back(RssMb());
      next_sample_ns_ += 10'000'000'000;
      if (rss_samples_.size() % 6 == 1 && rss_samples_.size() > 1) EndMinute();
    }
  }
  void Finish() {
    session.Finish();
    EndMinute();
  }

  hylo::run::Session session;
  OdometryPipeline& pipeline;  // session's
  std::vector<Minute> minutes;
  std::vector<double> rss_samples_;
  double sum_sq_ = 0.0, max_error_m_ = 0.0;
  std::size_t poses_ = 0;

 private:
  // Hybrid mode: the cells the added scans reach outside the prior's.
  void CountAdded(const hylo::odometry::ScanResult& r) {
    if (!hybrid_ || !r.map_updated || pipeline.map().run_size() == 0) return;
    for (const Eigen::Vector3f& p : r.registered_points_map) {
      const Eigen::Vector3f p_site = (T_site_map_ * p.cast<double>()).cast<float>();
      const int64_t cell = Cell(p_site);
      if (touched_.insert(cell).second && prior_cells_.count(cell) == 0) ++outside_prior_;
    }
  }

  void Score(const hylo::estimation::NavState& x) {
    // The true position at the state's time, linear between the 200 Hz truth samples.
    const auto later = std::lower_bound(
        truth_.begin(), truth_.end(), x.t_ns,
        [](const hylo::evaluation::TimedPose& p, int64_t t) { return p.t_ns < t; });
    if (later == truth_.begin() || later == truth_.end()) return;
    const auto& a = *(later - 1);
    const double w =
        static_cast<double>(x.t_ns - a.t_ns) / static_cast<double>(later->t_ns - a.t_ns);
    const Eigen::Vector3d p_true =
        (1.0 - w) * a.T_world_body.translation() + w * later->T_world_body.translation();
    const double e = (T_site_map_ * x.p_map_imu - p_true).norm();
    sum_sq_ += e * e;
    minute_sum_sq_ += e * e;
    ++poses_;
    ++minute_poses_;
    max_error_m_ = std::max(max_error_m_, e);
  }

  void EndMinute() {
    Minute m;
    m.rss_mb = rss_samples_.empty() ? RssMb() : rss_samples_.back();
    m.map_points = pipeline.map().Size();
    m.map_mb = pipeline.map().MemoryBytes() / 1e6;
    m.added_points = pipeline.map().run_size();
    m.touched_m2 = static_cast<double>(touched_.size());
    m.outside_prior_m2 = static_cast<double>(outside_prior_);
    m.ate_m = minute_poses_ > 0 ? std::sqrt(minute_sum_sq_ / minute_poses_) : 0.0;
    m.cpu_s = ProcessCpuS();
    minutes.push_back(m);
    std::printf(
        "  minute %3zu: RSS %8.1f MB, map %9zu points, %6.1f MB (%8zu added), area added "
        "%7.0f m^2 (%6.0f m^2 outside the prior), ATE %.4f m, CPU %7.1f s\n",
        minutes.size(), m.rss_mb, m.map_points, m.map_mb, m.added_points, m.touched_m2,
        m.outside_prior_m2, m.ate_m, m.cpu_s);
    std::fflush(stdout);
    minute_sum_sq_ = 0.0;
    minute_poses_ = 0;
  }

  Eigen::Isometry3d T_site_map_;
  const std::unordered_set<int64_t>& prior_cells_;
  bool hybrid_;
  std::deque<hylo::evaluation::TimedPose> truth_;
  std::unordered_set<int64_t> touched_;
  std::size_t outside_prior_ = 0;
  int64_t t0_ = -1;
  int64_t next_sample_ns_ = 0;
  double minute_sum_sq_ = 0.0;
  std::size_t minute_poses_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  using namespace hylo;
  double minutes = 60.0, column_deg = 0.0;
  std::string mode = "both", backend = "ieskf", json_path = "hour_benchmark.json";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--minutes" && has_value) {
      minutes = std::atof(argv[++i]);
    } else if (a == "--mode" && has_value) {
      mode = argv[++i];
    } else if (a == "--backend" && has_value) {
      backend = argv[++i];
    } else if (a == "--column-deg" && has_value) {
      column_deg = std::atof(argv[++i]);
    } else if (a == "--json" && has_value) {
      json_path = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: %s [--minutes M] [--mode localization|hybrid|both] "
                   "[--backend ieskf|sliding_window] [--column-deg D] [--json PATH]\n",
                   argv[0]);
      return 2;
    }
  }
  estimation::Estimator::Backend chosen;
  if (!(minutes > 0.0) || !estimation::ParseBackend(backend, &chosen) ||
      (mode != "localization" && mode != "hybrid" && mode != "both")) {
    std::fprintf(stderr, "bad --minutes, --mode or --backend\n");
    return 2;
  }

  // Session A as the seed-1 demo simulates it, mapped by SLAM (cached next to the binary).
  sim::SimulationOptions sim_options;
  if (column_deg > 0.0) sim_options.lidar.column_deg = column_deg;
  sim::Site site = sim::BuildSite(sim_options.seed, sim_options.terrain);
  const testing::SimPrior prior = testing::CachedSimPriorForThisBuild(
      sim_options, site,
      "hour_benchmark_prior_seed1_col" + std::to_string(sim_options.lidar.column_deg));
  std::unordered_set<int64_t> prior_cells;
  for (const Eigen::Vector3f& p : prior.points_map) {
    prior_cells.insert(Cell((prior.T_site_map * p.cast<double>()).cast<float>()));
  }
  std::printf("prior: SLAM on session A, %zu points (ATE %.4f m), %zu m^2 of 1 m cells\n",
              prior.points_map.size(), prior.slam_ate.rmse_m, prior_cells.size());

  // Session B's changed site, round the loop for the whole session (~4 min per lap).
  sim_options.duration_b_s = 60.0 * minutes;
  site.route_b = LoopRoute(static_cast<int>(std::ceil(minutes / 3.0)) + 1);
  const sim::SessionSimulator simulator(sim_options, site, sim::SessionId::kB);
  std::printf("route: %.0f m of loop for %.0f min\n", simulator.trajectory().path_length_m(),
              minutes);

  benchmarks::Report report;
  for (const std::string run_mode : {"localization", "hybrid"}) {
    if (mode != "both" && mode != run_mode) continue;
    const bool hybrid = run_mode == "hybrid";
    odometry::OdometryPipelineOptions options = testing::PipelineOptionsFor(sim_options);
    options.estimator.backend = chosen;
    options.localization.update_after_s = hybrid ? 10.0 : -1.0;
    options.output.dense_map_voxel_m = hybrid ? 1.0 : 0.0;  // the added area, in 1 m cells
    const double rss_before = RssMb();
    const double cpu_before = ProcessCpuS();
    HourSink sink(options, prior.T_site_map, prior_cells, hybrid);
    sink.pipeline.SetPriorMap(prior.points_map);
    // The true start in the map frame, moved by 0.5 m and 5 deg: a rough guess.
    Eigen::Isometry3d guess = prior.T_site_map.inverse() * simulator.trajectory().PoseAt(0);
    guess.translation() += Eigen::Vector3d(0.4, -0.3, 0.0);
    guess.linear() =
        Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()) * guess.linear();
    sink.pipeline.SetInitialGuess(guess);
    std::printf("\n%s (%s), %.0f min; RSS before %.1f MB\n", run_mode.c_str(), backend.c_str(),
                minutes, rss_before);
    simulator.Run(&sink);
    sink.Finish();
    if (sink.pipeline.status() == OdometryPipeline::Status::kFailed) {
      std::printf("FAILED: %s\n", sink.pipeline.message().c_str());
    }
    const std::vector<Minute>& m = sink.minutes;
    const std::size_t ref = std::min<std::size_t>(5, m.size()) - 1;  // minute 5 (or the last)
    double peak_after = 0.0;
    for (std::size_t i = ref; i < m.size(); ++i) peak_after = std::max(peak_after, m[i].rss_mb);
    const double growth = (m.back().rss_mb - m[ref].rss_mb) / m[ref].rss_mb;
    const double peak_growth = (peak_after - m[ref].rss_mb) / m[ref].rss_mb;
    const double ate = sink.poses_ > 0 ? std::sqrt(sink.sum_sq_ / sink.poses_) : 0.0;
    std::printf(
        "%s: ATE over the session %.4f m RMSE (max %.4f m, %zu poses); RSS minute %zu "
        "%.1f MB -> end %.1f MB (%+.2f %%, peak %+.2f %%); events %zu; CPU %.0f s\n",
        run_mode.c_str(), ate, sink.max_error_m_, sink.poses_, ref + 1, m[ref].rss_mb,
        m.back().rss_mb, 100.0 * growth, 100.0 * peak_growth, sink.pipeline.events().size(),
        ProcessCpuS() - cpu_before);
    if (hybrid) {
      // Growth against the area the added points cover: from the end of minute 1 (the
      // prior's and the pipeline's own memory in place) and from minute 5 on.
      for (const std::size_t from : {std::size_t{0}, ref}) {
        const Minute& a = m[from];
        const double area = m.back().touched_m2 - a.touched_m2;
        std::printf(
            "hybrid, minute %zu to the end: %+.0f m^2 of area added, %+.0f points, "
            "%+.2f MB map, %+.1f MB RSS (%.2f MB map per 1000 m^2)\n",
            from + 1, area, double(m.back().added_points) - double(a.added_points),
            m.back().map_mb - a.map_mb, m.back().rss_mb - a.rss_mb,
            area > 0.0 ? 1000.0 * (m.back().map_mb - a.map_mb) / area : 0.0);
      }
    }
    report.Set(run_mode, "minutes", static_cast<double>(m.size()));
    report.Set(run_mode, "ate_rmse_m", ate);
    report.Set(run_mode, "ate_max_m", sink.max_error_m_);
    report.Set(run_mode, "rss_minute5_mb", m[ref].rss_mb);
    report.Set(run_mode, "rss_end_mb", m.back().rss_mb);
    report.Set(run_mode, "map_mb_end", m.back().map_mb);
    report.Set(run_mode, "rss_growth_after_minute5", growth);
    report.Set(run_mode, "rss_peak_growth_after_minute5", peak_growth);
    report.Set(run_mode, "map_points_end", static_cast<double>(m.back().map_points));
    report.Set(run_mode, "added_points_end", static_cast<double>(m.back().added_points));
    report.Set(run_mode, "area_added_m2", m.back().touched_m2);
    report.Set(run_mode, "area_outside_prior_m2", m.back().outside_prior_m2);
    report.Set(run_mode, "cpu_s", ProcessCpuS() - cpu_before);
    report.Set(run_mode, "failed",
               sink.pipeline.status() == OdometryPipeline::Status::kFailed ? 1.0 : 0.0);
    for (std::size_t i = 0; i < m.size(); ++i) {
      const std::string k = "minute_" + std::to_string(i + 1);
      report.Set(run_mode + "_per_minute", k + "_rss_mb", m[i].rss_mb);
      report.Set(run_mode + "_per_minute", k + "_map_mb", m[i].map_mb);
      report.Set(run_mode + "_per_minute", k + "_added_points",
                 static_cast<double>(m[i].added_points));
      report.Set(run_mode + "_per_minute", k + "_area_added_m2", m[i].touched_m2);
      report.Set(run_mode + "_per_minute", k + "_ate_m", m[i].ate_m);
    }
  }
  if (!report.WriteJson(json_path)) std::fprintf(stderr, "cannot write %s\n", json_path.c_str());
  return 0;
}
