// Global localization on the simulated substation: session A mapped by SLAM, then vehicles
// standing anywhere on the mapped site (session B's changed world) localize from their first
// seconds of data without a guess.
//
// Groups of starts, each accepted pose judged against the truth (<= 10 cm and 1 deg): over the
// mapped site, in the annex whose plateau session A never mapped, on another seed of the site
// generator (the same layout slightly changed), and real scans of other places (any accepted
// pose there is wrong).
//
//   hylo_global_localization_benchmark [--quick] [--count N] [--outside N] [--seed N]
//       [--json PATH] [--dump CSV] [--only I,J,..] [--verbose] [--no-real]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "benchmark_common.h"
#include "estimation/sim_localization_util.h"
#include "global_scenes.h"
#include "hylo/io/cloud_io.h"
#include "hylo/mapping/ikd_tree.h"
#include "hylo/localization/global_localizer.h"
#include "hylo/localization/icp_initializer.h"
#include "hylo/registration/plane_matcher.h"
#include "hylo/registration/voxel_filter.h"
#include "test_data.h"

namespace {

using namespace hylo;
using benchmarks::NowMs;

struct Args {
  bool quick = false;
  int count = 120;         // starts over the mapped site
  int outside_count = 20;  // starts in the annex, and on another site
  uint64_t seed = 11;
  std::string json;
  std::string dump;               // CSV of every refined hypothesis's fit measures (gate studies)
  std::vector<int> only;          // run only these starts of each group (diagnosis)
  bool verbose = false;           // print every hypothesis against the truth
  bool real = true;               // the real scans of other places
  double sensor_height_m = -1.0;  // -1: the simulated vehicle's IMU height; 0: from the scan
  localization::GlobalLocalizerOptions global;
  localization::GlobalMapOptions raster;
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
    } else if (a == "--dump") {
      args.dump = next();
    } else if (a == "--outside") {
      args.outside_count = std::atoi(next().c_str());
    } else if (a == "--only") {
      const std::string list = next();
      for (std::size_t at = 0; at < list.size();) {
        const std::size_t comma = std::min(list.find(',', at), list.size());
        args.only.push_back(std::atoi(list.substr(at, comma - at).c_str()));
        at = comma + 1;
      }
    } else if (a == "--verbose") {
      args.verbose = true;
    } else if (a == "--no-real") {
      args.real = false;
    } else if (a == "--clearance") {
      args.global.ground_clearance_m = std::atof(next().c_str());
    } else if (a == "--sensor-height") {
      args.sensor_height_m = std::atof(next().c_str());
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
    } else if (a == "--hypotheses") {
      args.global.max_hypotheses = std::atoi(next().c_str());
    } else if (a == "--judge-iterations") {
      args.global.judge_icp_iterations = std::atoi(next().c_str());
    } else if (a == "--fine") {
      args.global.fine_hypotheses = std::atoi(next().c_str());
    } else if (a == "--refine-ratio") {
      args.global.refine_score_ratio = std::atof(next().c_str());
    } else if (a == "--max-points") {
      args.global.max_scan_points = std::atoi(next().c_str());
    } else {
      std::fprintf(stderr, "unknown argument %s\n", a.c_str());
      std::exit(2);
    }
  }
  if (args.quick) {
    args.count = std::min(args.count, 4);
    args.outside_count = 2;
  }
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
  view.R_level = localization::GuessFromGravity(Eigen::Vector3d::Zero(), 0.0, force).linear();
  return view;
}

// Fit measures of one refined hypothesis for gate studies (--dump): nearest-map distances of
// the thinned scan at the refined pose.
struct FitMeasures {
  double fit05 = 0, trim80 = 0, trim90 = 0, median_m = 0;
  double in10 = 0, in20 = 0, in30 = 0;
  double plane_fit = 0, plane05 = 0, plane10 = 0;  // point-to-plane: mean r^2, shares
};

FitMeasures Measure(const PointCloud& scan_fine, const registration::NeighborSearch& tree,
                    const Eigen::Isometry3d& T_map_imu) {
  std::vector<double> d2;
  std::vector<registration::Neighbor> nn;
  FitMeasures m;
  double plane_sum = 0;
  int plane_n = 0;
  for (const Eigen::Vector3f& p : scan_fine) {
    const Eigen::Vector3f q = (T_map_imu * p.cast<double>()).cast<float>();
    tree.KNearest(q, 5, 1.0f, &nn);
    d2.push_back(nn.empty() ? 1.0
                            : std::min(1.0, static_cast<double>(nn.front().squared_distance)));
    registration::Plane plane;
    if (nn.size() == 5 && nn.front().squared_distance <= 0.09 &&
        registration::FitPlane(nn, 0.1, &plane)) {
      const double r = plane.Distance(q.cast<double>());
      plane_sum += std::min(r * r, 0.09);
      ++plane_n;
      m.plane05 += std::abs(r) <= 0.05;
      m.plane10 += std::abs(r) <= 0.1;
    }
  }
  m.plane_fit = plane_n > 0 ? plane_sum / plane_n : 1.0;
  if (d2.empty()) return m;
  std::sort(d2.begin(), d2.end());
  double sum = 0;
  int within = 0;
  for (const double v : d2) {
    if (v <= 0.25) {
      sum += v;
      ++within;
    }
    m.in10 += v <= 0.01;
    m.in20 += v <= 0.04;
    m.in30 += v <= 0.09;
  }
  const double n = static_cast<double>(d2.size());
  m.fit05 = within > 0 ? sum / within : 1.0;
  m.plane05 /= n;
  m.plane10 /= n;
  m.in10 /= n;
  m.in20 /= n;
  m.in30 /= n;
  const auto trimmed = [&](double q) {
    const std::size_t k = std::max<std::size_t>(1, static_cast<std::size_t>(q * n));
    double s2 = 0;
    for (std::size_t i = 0; i < k; ++i) s2 += d2[i];
    return s2 / static_cast<double>(k);
  };
  m.trim80 = trimmed(0.8);
  m.trim90 = trimmed(0.9);
  m.median_m = std::sqrt(d2[d2.size() / 2]);
  return m;
}

// One line per refined hypothesis: where it lies against the truth and how it fits.
void DumpHypotheses(std::FILE* out, const char* group, std::size_t start,
                    const localization::GlobalLocalizationResult& r, const PointCloud& scan_imu,
                    const registration::NeighborSearch& tree, const Eigen::Isometry3d* T_true) {
  if (out == nullptr) return;
  const PointCloud scan_fine = registration::UniformSample(scan_imu, 0.2f);
  for (std::size_t i = 0; i < r.hypotheses.size(); ++i) {
    const localization::GlobalHypothesis& h = r.hypotheses[i];
    if (!h.refined) continue;
    double err_m = std::nan(""), err_deg = std::nan("");
    if (T_true != nullptr) {
      const Eigen::Isometry3d d = T_true->inverse() * h.T_refined;
      err_m = d.translation().norm();
      err_deg = Eigen::AngleAxisd(d.linear()).angle() * 180 / M_PI;
    }
    const FitMeasures m = Measure(scan_fine, tree, h.T_refined);
    std::fprintf(
        out,
        "%s,%zu,%zu,%s,%.4f,%.4f,%.3f,%d,%.5f,%.4f,%.5f,%.5f,%.5f,%.4f,%.4f,%.4f,%.4f,%.5f,%.4f,"
        "%.4f,%.4f\n",
        group, start, i, localization::ToString(r.status).c_str(), h.score, err_m, err_deg,
        h.passes ? 1 : 0, h.fitness_m2, h.inlier_ratio, m.fit05, m.trim80, m.trim90, m.median_m,
        m.in10, m.in20, m.in30, m.plane_fit, m.plane05, m.plane10, h.ground_support);
  }
  std::fflush(out);
}

std::FILE* g_dump = nullptr;  // --dump

// What one group of starts came to.
struct GroupResult {
  int correct = 0, wrong = 0, ambiguous = 0, not_found = 0, total = 0;
  std::vector<double> accept_ms;  // CPU time of Localize for each accepted start
  std::vector<double> all_ms;     // ... for every start
};

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

// Localizes the first seconds recorded at each start in session B's world of `site`; the
// truth moved by `T_map_site` judges each accepted pose.
GroupResult RunGroup(const char* name, const sim::SimulationOptions& sim_options,
                     const sim::Site& site, const std::vector<benchmarks::StartPose>& starts,
                     const Eigen::Isometry3d& T_map_site,
                     const localization::GlobalLocalizer& localizer,
                     const localization::GlobalMap& global_map,
                     const registration::NeighborSearch& tree, const Args& args) {
  GroupResult g;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    if (!args.only.empty() &&
        std::find(args.only.begin(), args.only.end(), static_cast<int>(k)) == args.only.end()) {
      continue;
    }
    const sim::SessionRecording rec =
        benchmarks::SimulateStart(sim_options, site, sim::SessionId::kB, starts[k], 2.05, 5.0);
    // The first 2 s: one second of IMU rest, then ten scans while still at rest.
    const StaticView view = ViewOf(rec, sim_options.lidar.T_imu_lidar, 10, 10);
    const localization::GlobalLocalizationResult r =
        localizer.Localize(view.scan_imu, view.R_level, global_map, tree);
    ++g.total;
    g.all_ms.push_back(r.elapsed_s * 1e3);
    const Eigen::Isometry3d T_truth = T_map_site * rec.truth.front().T_map_imu;
    DumpHypotheses(g_dump, name, k, r, view.scan_imu, tree, &T_truth);
    double err_m = -1, err_deg = -1;
    const char* verdict = "";
    if (r.status == localization::GlobalStatus::kAccepted) {
      g.accept_ms.push_back(r.elapsed_s * 1e3);
      const Eigen::Isometry3d T_true = T_map_site * rec.truth.front().T_map_imu;
      const Eigen::Isometry3d d = T_true.inverse() * r.T_map_imu;
      err_m = d.translation().norm();
      err_deg = Eigen::AngleAxisd(d.linear()).angle() * 180 / M_PI;
      const bool ok = err_m <= 0.1 && err_deg <= 1.0;
      verdict = ok ? "correct" : "WRONG";
      (ok ? g.correct : g.wrong)++;
    } else if (r.status == localization::GlobalStatus::kAmbiguous) {
      verdict = "ambiguous";
      ++g.ambiguous;
    } else {
      verdict = "not found";
      ++g.not_found;
    }
    std::printf(
        "%-8s %3zu (%6.1f, %5.1f) %4.0f deg: %-9s search %4.0f ms refine %4.0f ms "
        "err %.3f m %.2f deg | %s\n",
        name, k, starts[k].xy_m.x(), starts[k].xy_m.y(), starts[k].heading_rad * 180 / M_PI,
        verdict, r.stats.search_s * 1e3, r.refine_s * 1e3, err_m, err_deg, r.message.c_str());
    if (args.verbose) {
      for (const localization::GlobalHypothesis& h : r.hypotheses) {
        const Eigen::Isometry3d d = T_truth.inverse() * h.T_map_imu;
        const Eigen::Isometry3d dr = T_truth.inverse() * h.T_refined;
        const Eigen::Isometry3d dc = T_truth.inverse() * h.T_coarse;
        std::printf("    score %.3f search err %.2f m %.1f deg, coarse err %.2f m inliers %.3f%s",
                    h.score, d.translation().norm(),
                    Eigen::AngleAxisd(d.linear()).angle() * 180 / M_PI, dc.translation().norm(),
                    h.coarse_inlier_ratio, h.refined ? "" : "\n");
        if (h.refined) {
          std::printf(" -> refined err %.3f m %.2f deg %s inliers %.3f plane %.5f fitness %.5f\n",
                      dr.translation().norm(), Eigen::AngleAxisd(dr.linear()).angle() * 180 / M_PI,
                      h.passes ? "passes" : "fails", h.inlier_ratio, h.plane_fitness_m2,
                      h.fitness_m2);
        }
      }
      std::printf("    sensor height %.2f m, %zu scan points, %zu voxels, %zu nodes, %zu columns\n",
                  r.stats.sensor_height_m, r.stats.scan_points, r.stats.scan_voxels,
                  r.stats.nodes_scored, r.stats.columns_scored);
    }
    std::fflush(stdout);
  }
  return g;
}

// Real scans of other places (the data README's hand-held walk and Velodyne pair), each
// localized alone, levelled as a ground vehicle would be (no IMU): any accept is wrong.
GroupResult RunRealScans(const localization::GlobalLocalizer& localizer,
                         const localization::GlobalMap& global_map,
                         const registration::NeighborSearch& tree) {
  GroupResult g;
  std::vector<std::string> paths;
  for (const char* dir : {"balm_scans", "balm_scans_40_59", "balm_scans_100_119"}) {
    const std::filesystem::path folder = hylo::testing::DataPath(dir);
    if (!std::filesystem::is_directory(folder)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
      if (entry.path().extension() == ".pcd") paths.push_back(entry.path().string());
    }
  }
  for (const char* name : {"scan_pair/source.pcd", "scan_pair/target.pcd"}) {
    if (std::filesystem::exists(hylo::testing::DataPath(name)))
      paths.push_back(hylo::testing::DataPath(name));
  }
  std::sort(paths.begin(), paths.end());
  if (paths.empty())
    std::printf("real scans: data absent (%s), group skipped\n", hylo::testing::DataDir().c_str());
  for (const std::string& path : paths) {
    PointCloud scan;
    for (const Eigen::Vector3d& p : io::ReadCloud(path).positions) scan.push_back(p.cast<float>());
    const localization::GlobalLocalizationResult r =
        localizer.Localize(scan, Eigen::Matrix3d::Identity(), global_map, tree);
    ++g.total;
    g.all_ms.push_back(r.elapsed_s * 1e3);
    DumpHypotheses(g_dump, "real", g.total, r, scan, tree, nullptr);
    if (r.status == localization::GlobalStatus::kAccepted) {
      ++g.wrong;
      g.accept_ms.push_back(r.elapsed_s * 1e3);
    } else if (r.status == localization::GlobalStatus::kAmbiguous) {
      ++g.ambiguous;
    } else {
      ++g.not_found;
    }
    std::printf("real     %s: %s\n", std::filesystem::path(path).filename().c_str(),
                r.message.c_str());
    std::fflush(stdout);
  }
  return g;
}

void Summarize(const char* name, const GroupResult& g, benchmarks::Report* report) {
  report->Set(name, "starts", g.total);
  report->Set(name, "correct", g.correct);
  report->Set(name, "wrong", g.wrong);
  report->Set(name, "ambiguous", g.ambiguous);
  report->Set(name, "not_found", g.not_found);
  report->Set(name, "correct_pct", g.total > 0 ? 100.0 * g.correct / g.total : 0.0);
  report->Set(name, "accepted_cpu_ms_median", Quantile(g.accept_ms, 0.5));
  report->Set(name, "accepted_cpu_ms_p95", Quantile(g.accept_ms, 0.95));
  report->Set(name, "all_cpu_ms_median", Quantile(g.all_ms, 0.5));
  report->Set(name, "all_cpu_ms_p95", Quantile(g.all_ms, 0.95));
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = Parse(argc, argv);
  if (!args.dump.empty()) {
    g_dump = std::fopen(args.dump.c_str(), "w");
    if (g_dump == nullptr) {
      std::fprintf(stderr, "cannot write %s\n", args.dump.c_str());
      return 1;
    }
    std::fprintf(g_dump,
                 "group,start,hyp,status,score,err_m,err_deg,passes,fitness,inliers,"
                 "fit05,trim80,trim90,median_m,in10,in20,in30,plane_fit,plane05,plane10,"
                 "ground_support\n");
  }
  const sim::SimulationOptions sim_options;
  const sim::Site site = sim::BuildSite(sim_options.seed, sim_options.terrain);
  double t0 = NowMs();
  const hylo::testing::SimPrior prior =
      hylo::testing::CachedSimPriorForThisBuild(sim_options, site, "global_benchmark_prior_seed1");
  std::printf("prior map (SLAM on session A): %zu points, %.1f s\n", prior.points_map.size(),
              (NowMs() - t0) / 1e3);
  benchmarks::Report report;
  const std::size_t heap0 = benchmarks::HeapBytes();
  t0 = NowMs();
  const localization::GlobalMap global_map =
      localization::GlobalMap::Build(prior.points_map, args.raster);
  const double prepare_ms = NowMs() - t0;
  report.Set("map", "points", static_cast<double>(prior.points_map.size()));
  report.Set("map", "raster_cells",
             static_cast<double>(global_map.layout().width) * global_map.layout().height);
  report.Set("map", "prepare_cpu_ms", prepare_ms);
  report.Set("map", "pyramid_mb", global_map.MemoryBytes() / 1e6);
  report.Set("map", "prepare_heap_mb",
             (static_cast<double>(benchmarks::HeapBytes()) - static_cast<double>(heap0)) / 1e6);
  mapping::IkdTree tree{mapping::IkdTree::Options()};
  tree.Build(prior.points_map);

  const sim::World world_b(site.terrain, sim::SessionPrimitives(site, sim::SessionId::kB),
                           sim_options.index_cell_m);
  PointCloud map_site;
  for (const Eigen::Vector3f& p : prior.points_map) {
    map_site.push_back((prior.T_site_map * p.cast<double>()).cast<float>());
  }
  const Eigen::Isometry3d T_map_site = prior.T_site_map.inverse();
  // The IMU's height above the wheels is a constant of the vehicle, set like its extrinsic.
  localization::GlobalLocalizerOptions global = args.global;
  global.sensor_height_m =
      args.sensor_height_m < 0.0 ? sim_options.trajectory.imu_height_m : args.sensor_height_m;
  std::printf("sensor height: %s\n", global.sensor_height_m > 0.0
                                         ? std::to_string(global.sensor_height_m).c_str()
                                         : "estimated from each scan");
  report.Set("map", "sensor_height_m", global.sensor_height_m);
  const localization::GlobalLocalizer localizer(global, localization::IcpInitializerOptions());

  // Over the mapped site: everywhere session A's map has ground, the annex left out.
  benchmarks::StartRegion mapped;
  mapped.min_m = {2.0, 2.0};
  mapped.max_m = {118.0, 78.0};
  mapped.exclude_min_m = site.annex_min_m.array() - 2.0;
  mapped.exclude_max_m = site.annex_max_m.array() + 2.0;
  const GroupResult in_map =
      RunGroup("mapped", sim_options, site,
               benchmarks::SampleStartPoses(world_b, map_site, mapped, args.count, args.seed),
               T_map_site, localizer, global_map, tree, args);

  // In the annex: its plateau ground was never mapped, but session A saw its bank faces and
  // tall objects from below. An accepted pose is judged against the truth like any other.
  benchmarks::StartRegion annex;
  annex.min_m = site.annex_min_m.array() + 3.0;
  annex.max_m = site.annex_max_m.array() - 3.0;
  annex.spacing_m = 4.0;
  const GroupResult in_annex = RunGroup(
      "annex", sim_options, site,
      benchmarks::SampleStartPoses(world_b, PointCloud(), annex, args.outside_count, args.seed),
      T_map_site, localizer, global_map, tree, args);

  // Another seed of the generator: the same lanes and bays, equipment moved by up to 0.15 m
  // and other terrain undulations; the same place changed slightly, not another site. An
  // accepted pose here is reported, and judged against where the start lies on this site.
  const sim::Site other = sim::BuildSite(sim_options.seed + 100, sim_options.terrain);
  const sim::World world_other(other.terrain, sim::SessionPrimitives(other, sim::SessionId::kB),
                               sim_options.index_cell_m);
  const GroupResult elsewhere =
      RunGroup("seed", sim_options, other,
               benchmarks::SampleStartPoses(world_other, PointCloud(), mapped, args.outside_count,
                                            args.seed),
               T_map_site, localizer, global_map, tree, args);

  const GroupResult real = args.real ? RunRealScans(localizer, global_map, tree) : GroupResult();

  Summarize("mapped", in_map, &report);
  Summarize("annex", in_annex, &report);
  Summarize("other_seed", elsewhere, &report);
  Summarize("real_scans", real, &report);
  report.Print(std::cout);
  if (!args.json.empty() && !report.WriteJson(args.json)) {
    std::fprintf(stderr, "cannot write %s\n", args.json.c_str());
    return 1;
  }
  return 0;
}
