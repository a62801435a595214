// Global localization on the simulated substation: session A mapped by SLAM, then vehicles
// standing anywhere on the mapped site (session B's changed world) localize from their first
// seconds of data without a guess.
//
//   hylo_global_localization_benchmark [--quick] [--count N] [--seed N] [--json PATH]

#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "benchmark_common.h"
#include "estimation/sim_localization_util.h"
#include "global_scenes.h"
#include "hylo/mapping/ikd_tree.h"
#include "hylo/registration/global_localizer.h"
#include "hylo/registration/icp_initializer.h"

namespace {

using namespace hylo;
using benchmarks::NowMs;

struct Args {
  bool quick = false;
  int count = 120;
  uint64_t seed = 11;
  std::string json;
  registration::GlobalLocalizerOptions global;
  registration::GlobalMapOptions raster;
};

Args Parse(int argc, char** argv) {
  Args args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() { return std::string(i + 1 < argc ? argv[++i] : ""); };
    if (a == "--quick") {
      args.quick = true;
    } else if (a == "--count") {
      args.count = std::atoi(next().c_str());
    } else if (a == "--seed") {
      args.seed = std::strtoull(next().c_str(), nullptr, 10);
    } else if (a == "--json") {
      args.json = next();
    } else if (a == "--clearance") {
      args.global.ground_clearance_m = std::atof(next().c_str());
    } else if (a == "--z-tol") {
      args.global.z_tolerance_m = std::atof(next().c_str());
    } else if (a == "--max-range") {
      args.global.max_range_m = std::atof(next().c_str());
    } else if (a == "--yaw-step") {
      args.global.yaw_step_deg = std::atof(next().c_str());
    } else if (a == "--cell") {
      args.raster.cell_m = std::atof(next().c_str());
    } else if (a == "--z-bin") {
      args.raster.z_bin_m = std::atof(next().c_str());
    } else if (a == "--max-points") {
      args.global.max_scan_points = std::atoi(next().c_str());
    } else {
      std::fprintf(stderr, "unknown argument %s\n", a.c_str());
      std::exit(2);
    }
  }
  if (args.quick) args.count = std::min(args.count, 4);
  return args;
}

// The static scans of a recording (the first second after the IMU's one-second rest) in the
// IMU frame, and the levelling rotation from the mean specific force over that time.
struct StaticView {
  PointCloud scan_imu;
  Eigen::Matrix3d R_level = Eigen::Matrix3d::Identity();
};

StaticView ViewOf(const sim::SessionRecording& rec, const Eigen::Isometry3d& T_imu_lidar,
                  int first_scan, int scans) {
  StaticView view;
  for (int i = first_scan; i < first_scan + scans && i < static_cast<int>(rec.scans.size()); ++i) {
    for (const ScanPoint& p : rec.scans[static_cast<std::size_t>(i)].points) {
      view.scan_imu.push_back((T_imu_lidar * p.position_lidar.cast<double>()).cast<float>());
    }
  }
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (const ImuSample& s : rec.imu) force += s.accel_imu;
  view.R_level = registration::GuessFromGravity(Eigen::Vector3d::Zero(), 0.0, force).linear();
  return view;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = Parse(argc, argv);
  const sim::SimulationOptions sim_options;
  const sim::Site site = sim::BuildSite(sim_options.seed, sim_options.terrain);
  double t0 = NowMs();
  // Keyed by this build of the benchmark, so a changed pipeline never meets a stale prior.
  struct stat exe {};
  ::stat("/proc/self/exe", &exe);
  const testing::SimPrior prior = testing::CachedSimPrior(
      sim_options, site,
      std::string(HYLO_BINARY_DIR) + "/global_benchmark_prior_seed1_" +
          std::to_string(exe.st_mtime) + ".bin");
  std::printf("prior map (SLAM on session A): %zu points, %.1f s\n", prior.points_map.size(),
              (NowMs() - t0) / 1e3);
  const std::size_t heap0 = benchmarks::HeapBytes();
  t0 = NowMs();
  const registration::GlobalMap global_map = registration::GlobalMap::Build(prior.points_map,
                                                                            args.raster);
  const double prepare_ms = NowMs() - t0;
  std::printf("global map: %d x %d cells, %.1f MB, prepared in %.0f ms (heap +%.1f MB)\n",
              global_map.layout().width, global_map.layout().height,
              global_map.MemoryBytes() / 1e6, prepare_ms,
              (benchmarks::HeapBytes() - heap0) / 1e6);
  mapping::IkdTree tree{mapping::IkdTree::Options()};
  tree.Build(prior.points_map);

  const sim::World world_b(site.terrain, sim::SessionPrimitives(site, sim::SessionId::kB),
                           sim_options.index_cell_m);
  PointCloud map_site;
  for (const Eigen::Vector3f& p : prior.points_map) {
    map_site.push_back((prior.T_site_map * p.cast<double>()).cast<float>());
  }
  benchmarks::StartRegion region;
  region.min_m = {2.0, 2.0};
  region.max_m = {118.0, 78.0};
  region.exclude_min_m = {98.0, 0.0};
  region.exclude_max_m = {120.0, 42.0};
  const std::vector<benchmarks::StartPose> starts =
      benchmarks::SampleStartPoses(world_b, map_site, region, args.count, args.seed);
  std::printf("%zu start poses\n", starts.size());

  const registration::GlobalLocalizer localizer(args.global,
                                                registration::IcpInitializerOptions());
  int correct = 0, ambiguous = 0, not_found = 0, wrong = 0;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const sim::SessionRecording rec = benchmarks::SimulateStart(
        sim_options, site, sim::SessionId::kB, starts[k], 2.05, 5.0);
    const StaticView view = ViewOf(rec, sim_options.lidar.T_imu_lidar, 10, 10);
    const Eigen::Isometry3d T_true = prior.T_site_map.inverse() * rec.truth.front().T_map_imu;
    const registration::GlobalLocalizationResult r =
        localizer.Localize(view.scan_imu, view.R_level, global_map, tree);
    double err_m = -1, err_deg = -1;
    // Where the true pose ranks among the search's hypotheses (-1: absent).
    int rank = -1;
    for (std::size_t i = 0; i < r.hypotheses.size(); ++i) {
      const Eigen::Isometry3d d = T_true.inverse() * r.hypotheses[i].T_map_imu;
      if (rank < 0 && d.translation().head<2>().norm() < 1.0 &&
          Eigen::AngleAxisd(d.linear()).angle() < 5.0 * M_PI / 180) {
        rank = static_cast<int>(i);
      }
    }
    const char* verdict = "";
    if (r.status == registration::GlobalStatus::kAccepted) {
      const Eigen::Isometry3d d = T_true.inverse() * r.T_map_imu;
      err_m = d.translation().norm();
      err_deg = Eigen::AngleAxisd(d.linear()).angle() * 180 / M_PI;
      const bool ok = err_m <= 0.1 && err_deg <= 1.0;
      verdict = ok ? "correct" : "WRONG";
      const Eigen::AngleAxisd aa(d.linear());
      std::printf("    d_t %.3f %.3f %.3f axis %.2f %.2f %.2f\n", d.translation().x(),
                  d.translation().y(), d.translation().z(), aa.axis().x(), aa.axis().y(),
                  aa.axis().z());
      (ok ? correct : wrong)++;
    } else if (r.status == registration::GlobalStatus::kAmbiguous) {
      verdict = "ambiguous";
      ++ambiguous;
    } else {
      verdict = "not found";
      ++not_found;
    }
    std::printf("%3zu (%6.1f, %5.1f) %4.0f deg: %-9s rank %2d top %.3f 2nd %.3f search %.0f ms "
                "refine %.0f ms voxels %zu nodes %zu err %.3f m %.2f deg | %s\n",
                k, starts[k].xy_m.x(), starts[k].xy_m.y(), starts[k].heading_rad * 180 / M_PI,
                verdict, rank, r.hypotheses.empty() ? 0.0 : r.hypotheses[0].score,
                r.hypotheses.size() > 1 ? r.hypotheses[1].score : 0.0, r.stats.search_s * 1e3,
                r.refine_s * 1e3, r.stats.scan_voxels, r.stats.nodes_scored, err_m, err_deg,
                r.message.c_str());
    std::fflush(stdout);
  }
  std::printf("correct %d, ambiguous %d, not found %d, WRONG %d of %zu\n", correct, ambiguous,
              not_found, wrong, starts.size());
  return 0;
}
