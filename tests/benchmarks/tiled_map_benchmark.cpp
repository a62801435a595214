// Prior maps larger than memory: a > 100 M-point synthetic map (the simulated substation
// repeated over ~1.1 km x 1.0 km, surfaces sampled every 0.1 m) cut by `hylo tile`, and a
// simulated 1 km drive localized in it by `hylo localize` with the tiles streamed around the
// vehicle. Every figure comes from the real tools run in processes of their own:
//  - `hylo tile` on the whole map: points per second, peak memory;
//  - the drive in the tiled map: peak RSS and RSS sampled over the drive, time from the
//    start to the first accepted pose, per-scan CPU (median, p99), ATE against the truth;
//  - the first 200 m of the drive in the tiled map and in an in-memory map of the same
//    corridor (every tile the window holds on that stretch, one PCD loaded whole): per-scan
//    CPU p99 ratio, ATE of both;
//  - whole-map loading at three corridor sizes (as far as memory allows on a shared machine:
//    the 100 M map is never loaded whole), fitted and extrapolated to the whole map.
// Everything is generated once into --work (default /tmp/hylo_tiled_bench, ~8 GB) and reused;
// the measurements run every time. Prints the figures and writes JSON (--json).
//
//   hylo_tiled_map_benchmark [--work DIR] [--json PATH] [--quick] [--generate-only]
//                            [--reuse-tiles]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "benchmark_common.h"
#include "hylo/config/run_config.h"
#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/cloud_stream.h"
#include "hylo/io/json.h"
#include "hylo/io/trajectory_io.h"
#include "hylo/sim_io/session_writer.h"
#include "hylo/tiles/tiled_map.h"
#include "hylo/tiles/tiles.h"
#include "measured_child.h"
#include "repeated_site.h"

namespace hylo::benchmarks {
namespace {

namespace fs = std::filesystem;

const std::string kHylo = std::string(HYLO_BINARY_DIR) + "/apps/hylo";
constexpr uint64_t kSeed = 1;
constexpr double kSpeedMps = 2.0;

struct Setup {
  std::string work, map, tiles, config, config_no_global, full_bag, full_truth, short_bag,
      short_truth;
  Eigen::Vector2d road_start, road_end;
  double short_length_m = 200.0;
};

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The world, the map and both drives, made once.
Setup Generate(const std::string& work, bool quick, Report* report) {
  Setup s;
  s.work = work;
  s.map = work + "/map.pcd";
  s.tiles = work + "/tiles";
  s.config = work + "/config.yaml";
  s.config_no_global = work + "/config_no_global.yaml";
  fs::create_directories(work);
  RepeatedSiteOptions layout;
  if (quick) layout.copies_x = layout.copies_y = 2;
  const double x = RoadX(layout, layout.copies_x / 2 - 1);
  s.road_start = Eigen::Vector2d(x, -5.0);
  s.road_end = Eigen::Vector2d(x, layout.copies_y * layout.period_m.y() - 30.0);
  if (quick) s.short_length_m = 60.0;
  // The world is built only when something is missing (its terrain takes minutes).
  std::unique_ptr<sim::Site> site;
  auto world = [&]() -> const sim::Site& {
    if (site == nullptr) {
      const auto t0 = std::chrono::steady_clock::now();
      const sim::Site base = sim::BuildSite(kSeed, sim::TerrainOptions());
      site = std::make_unique<sim::Site>(
          RepeatedSite(base, layout, {s.road_start, s.road_end}, kSeed));
      report->Set("generation", "terrain_s", Seconds(t0));
    }
    return *site;
  };
  report->Set("generation", "copies", layout.copies_x * layout.copies_y);
  report->Set(
      "generation", "area_km2",
      (layout.copies_x * layout.period_m.x()) * (layout.copies_y * layout.period_m.y()) * 1e-6);
  if (!fs::exists(s.map)) {
    const auto t0 = std::chrono::steady_clock::now();
    const SiteMapSummary m = WriteSiteMap(world(), s.map, 0.1, 0.1, kSeed);
    std::printf("map: %zu ground + %zu object points in %.0f s\n", m.ground_points, m.object_points,
                Seconds(t0));
  }
  sim::SimulationOptions options;
  options.seed = kSeed;
  options.trajectory.cruise_speed_mps = kSpeedMps;
  const double length = (s.road_end - s.road_start).norm();
  for (const bool full : {true, false}) {
    const std::string dir = work + (full ? "/drive_full" : "/drive_short");
    options.duration_b_s =
        options.trajectory.standstill_s + 5.0 + (full ? length : s.short_length_m) / kSpeedMps;
    (full ? s.full_bag : s.short_bag) = sim::SessionBagPath(dir, sim::SessionId::kB);
    (full ? s.full_truth : s.short_truth) = sim::SessionTruthPath(dir, sim::SessionId::kB);
    if (fs::exists(sim::SessionManifestPath(dir, sim::SessionId::kB))) continue;
    const auto t0 = std::chrono::steady_clock::now();
    const sim::SessionSummary d = sim::WriteSession(options, world(), sim::SessionId::kB, dir);
    std::printf("drive %s: %zu scans, %.0f m in %.0f s\n", dir.c_str(), d.scans, d.path_length_m,
                Seconds(t0));
  }
  config::RunConfig config =
      config::LoadRunConfig(std::string(HYLO_SOURCE_DIR) + "/config/presets/sim_vlp16.yaml");
  // A dense map of every registered scan grows with the drive; a memory benchmark leaves it out.
  config.pipeline.output.dense_map_voxel_m = 0.0;
  config::SaveRunConfig(s.config, config);
  // The global localizer's raster covers the whole map: its share of the memory, measured.
  config.pipeline.localization.global_enabled = false;
  config::SaveRunConfig(s.config_no_global, config);
  return s;
}

// The drive's true start, off by 0.5 m and 3 deg, as "x y z roll pitch yaw" (m, deg).
std::string Guess(const std::string& truth_path) {
  const Eigen::Isometry3d T = io::ReadTum(truth_path).front().T_world_body();
  const Eigen::Matrix3d R = T.rotation();
  const double deg = 180.0 / M_PI;
  char text[200];
  std::snprintf(text, sizeof(text), "%.3f %.3f %.3f %.4f %.4f %.4f", T.translation().x() + 0.5,
                T.translation().y() - 0.5, T.translation().z(), std::atan2(R(2, 1), R(2, 2)) * deg,
                std::asin(-R(2, 0)) * deg, std::atan2(R(1, 0), R(0, 0)) * deg + 3.0);
  return text;
}

std::vector<evaluation::TimedPose> Timed(const std::vector<io::StampedPose>& poses) {
  std::vector<evaluation::TimedPose> timed;
  for (const io::StampedPose& p : poses) timed.push_back({p.t_ns, p.T_world_body()});
  return timed;
}

struct Localized {
  ChildRun child;
  io::Json summary;
  double ate_m = std::nan("");
};

Localized Localize(const Setup& s, const std::string& bag, const std::string& truth,
                   const std::string& map, const std::string& name, bool global = true) {
  const std::string out = s.work + "/runs/" + name;
  fs::remove_all(out);
  fs::create_directories(out);
  Localized r;
  r.child =
      RunMeasured({kHylo, "localize", "--log", bag, "--map", map, "--config",
                   global ? s.config : s.config_no_global, "--guess", Guess(truth), "--out", out},
                  s.work + "/runs/" + name + ".log");
  if (r.child.exit_code != 0 || !fs::exists(out + "/summary.json")) {
    std::printf("%s: hylo localize exited %d (see %s.log)\n", name.c_str(), r.child.exit_code,
                (s.work + "/runs/" + name).c_str());
    return r;
  }
  r.summary = io::ReadJsonFile(out + "/summary.json");
  const evaluation::AteResult ate = evaluation::ComputeAte(
      Timed(io::ReadTum(out + "/trajectory.tum")), Timed(io::ReadTum(truth)));
  if (ate.ok) r.ate_m = ate.rmse_m;
  return r;
}

void ReportRun(const std::string& section, const Localized& r, Report* report) {
  report->Set(section, "exit_code", r.child.exit_code);
  report->Set(section, "peak_rss_mb", r.child.peak_rss_mb);
  report->Set(section, "wall_s", r.child.wall_s);
  report->Set(section, "cpu_s", r.child.cpu_s);
  report->Set(section, "prior_map_loaded_after_s",
              io::NumberAt(r.summary, "prior_map_loaded_after_s"));
  report->Set(section, "first_pose_after_s", io::NumberAt(r.summary, "first_pose_after_s"));
  report->Set(section, "first_pose_cpu_s", io::NumberAt(r.summary, "first_pose_cpu_s"));
  report->Set(section, "cpu_ms_per_scan_median", io::NumberAt(r.summary, "cpu_ms_per_scan_median"));
  report->Set(section, "cpu_ms_per_scan_p99", io::NumberAt(r.summary, "cpu_ms_per_scan_p99"));
  report->Set(section, "scans", io::NumberAt(r.summary, "scans_processed"));
  report->Set(section, "path_m", io::NumberAt(r.summary, "path_length_m"));
  report->Set(section, "ate_m", r.ate_m);
  report->Set(section, "prior_points", io::NumberAt(r.summary, "prior_map_points"));
  for (const char* key : {"max_points_held", "max_tiles_held", "tiles_loaded", "tiles_unloaded",
                          "loader_cpu_s", "load_radius_m"}) {
    const double v = io::NumberAt(r.summary, std::string("prior_map_tiles.") + key);
    if (std::isfinite(v)) report->Set(section, key, v);
  }
}

// RSS over the drive, after the start: medians early and late, the largest, and the slope.
void ReportRssOverTime(const std::string& section, const Localized& r, Report* report) {
  const double start = io::NumberAt(r.summary, "first_pose_after_s");
  std::vector<RssSample> after;
  for (const RssSample& x : r.child.rss) {
    if (x.t_s >= start) after.push_back(x);
  }
  if (after.size() < 20) return;
  auto median_between = [&](double a, double b) {
    std::vector<double> v;
    for (std::size_t i = 0; i < after.size(); ++i) {
      const double f = static_cast<double>(i) / after.size();
      if (f >= a && f < b) v.push_back(after[i].rss_mb);
    }
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  // The slope once the window has filled (the last three quarters of the drive).
  double st = 0, sr = 0, stt = 0, str = 0, max_rss = 0;
  const std::vector<RssSample> late(after.begin() + after.size() / 4, after.end());
  for (const RssSample& x : after) max_rss = std::max(max_rss, x.rss_mb);
  for (const RssSample& x : late) {
    st += x.t_s;
    sr += x.rss_mb;
    stt += x.t_s * x.t_s;
    str += x.t_s * x.rss_mb;
  }
  const double n = static_cast<double>(late.size());
  const double slope = (n * str - st * sr) / (n * stt - st * st);
  report->Set(section, "rss_first_decile_mb", median_between(0.0, 0.1));
  report->Set(section, "rss_mid_mb", median_between(0.45, 0.55));
  report->Set(section, "rss_last_decile_mb", median_between(0.9, 1.0));
  report->Set(section, "rss_max_after_start_mb", max_rss);
  report->Set(section, "rss_slope_last_3_quarters_mb_per_min", 60.0 * slope);
  report->Set(section, "rss_minutes_after_start", (after.back().t_s - after.front().t_s) / 60.0);
}

// The corridor of the first `length_m` of the road: every tile within `radius_m`, written
// whole (world frame) in nested crops of 1/4, 1/2 and all of its points, nearest first.
std::vector<std::pair<std::string, std::size_t>> WriteCorridors(const Setup& s, double radius_m) {
  const tiles::TiledMapIndex index = tiles::ReadTiledMapIndex(s.tiles);
  const tiles::TileGrid grid(index.tile_size_m);
  const Eigen::Vector3d a(s.road_start.x(), s.road_start.y(), 0.0);
  std::vector<std::pair<double, const tiles::TiledMapTile*>> near;
  for (const tiles::TiledMapTile& t : index.tiles) {
    double best = 1e300;
    for (double y = 0.0; y <= s.short_length_m; y += 1.0) {
      const Eigen::Vector3d p = a + Eigen::Vector3d(0.0, y, 0.0) - index.origin_world;
      best = std::min(best, grid.SquaredDistanceTo({t.ix, t.iy}, p.cast<float>()));
    }
    if (best <= radius_m * radius_m) near.emplace_back(best, &t);
  }
  std::sort(near.begin(), near.end());
  std::size_t total = 0;
  for (const auto& n : near) total += n.second->points;
  std::vector<std::pair<std::string, std::size_t>> written;
  for (const int quarter : {1, 2, 4}) {
    const std::string path = s.work + "/corridor_" + std::to_string(quarter) + "q.pcd";
    io::PcdXyzWriter writer(path);
    for (const auto& [d2, tile] : near) {
      if (writer.points() >= total * quarter / 4) break;
      PointCloud world;
      for (const Eigen::Vector3f& p : tiles::ReadTiledMapTile(s.tiles, index.origin_world, *tile)) {
        world.push_back((p.cast<double>() + index.origin_world).cast<float>());
      }
      writer.Add(world);
    }
    written.emplace_back(path, writer.points());
    writer.Commit();
  }
  return written;
}

}  // namespace
}  // namespace hylo::benchmarks

int main(int argc, char** argv) {
  using namespace hylo::benchmarks;
  std::string work = "/tmp/hylo_tiled_bench", json;
  bool quick = false, generate_only = false, reuse_tiles = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") quick = true;
    if (a == "--generate-only") generate_only = true;
    if (a == "--reuse-tiles") reuse_tiles = true;
    if (a == "--work" && i + 1 < argc) work = argv[++i];
    if (a == "--json" && i + 1 < argc) json = argv[++i];
  }
  if (quick && work == "/tmp/hylo_tiled_bench") work += "_quick";
  if (json.empty()) json = work + "/tiled_map_benchmark.json";
  Report report;
  const Setup s = Generate(work, quick, &report);
  if (generate_only) return 0;
  report.Set("map", "file_gb", fs::file_size(s.map) / 1e9);
  report.Set("map", "points", hylo::io::ReadCloudInfo(s.map).points);

  // `hylo tile` on the whole map (--reuse-tiles: the tiles of an earlier run, not measured).
  if (!reuse_tiles || !hylo::tiles::IsTiledMap(s.tiles)) {
    const ChildRun tile = RunMeasured(
        {kHylo, "tile", "--in", s.map, "--out", s.tiles, "--json", s.work + "/tile.json"},
        s.work + "/tile.log");
    const hylo::io::Json t = hylo::io::ReadJsonFile(s.work + "/tile.json");
    report.Set("hylo_tile", "exit_code", tile.exit_code);
    report.Set("hylo_tile", "points_read", hylo::io::NumberAt(t, "points_read"));
    report.Set("hylo_tile", "points_written", hylo::io::NumberAt(t, "points_written"));
    report.Set("hylo_tile", "tiles", hylo::io::NumberAt(t, "tiles"));
    report.Set("hylo_tile", "wall_s", tile.wall_s);
    report.Set("hylo_tile", "cpu_s", tile.cpu_s);
    report.Set("hylo_tile", "points_per_s_wall",
               hylo::io::NumberAt(t, "points_read") / tile.wall_s);
    report.Set("hylo_tile", "points_per_s_cpu", hylo::io::NumberAt(t, "points_read") / tile.cpu_s);
    report.Set("hylo_tile", "peak_rss_mb", tile.peak_rss_mb);
  }
  report.Set("tiles", "points", hylo::tiles::ReadTiledMapIndex(s.tiles).points);
  report.Set("tiles", "tiles", hylo::tiles::ReadTiledMapIndex(s.tiles).tiles.size());

  const Localized full = Localize(s, s.full_bag, s.full_truth, s.tiles, "tiled_full");
  ReportRun("drive_tiled", full, &report);
  ReportRssOverTime("drive_tiled", full, &report);

  const Localized tiled = Localize(s, s.short_bag, s.short_truth, s.tiles, "tiled_short");
  ReportRun("short_tiled", tiled, &report);
  const Localized no_global =
      Localize(s, s.short_bag, s.short_truth, s.tiles, "tiled_short_no_global", false);
  ReportRun("short_tiled_no_global_raster", no_global, &report);
  const double radius = hylo::io::NumberAt(tiled.summary, "prior_map_tiles.load_radius_m");
  std::vector<std::pair<double, double>> points_rss;
  Localized whole;
  for (const auto& [path, points] : WriteCorridors(s, std::isfinite(radius) ? radius : 102.0)) {
    const std::string name = fs::path(path).stem().string();
    whole = Localize(s, s.short_bag, s.short_truth, path, "whole_" + name);
    ReportRun("short_whole_" + name, whole, &report);
    points_rss.emplace_back(static_cast<double>(points), whole.child.peak_rss_mb);
  }
  // Peak RSS of whole-map loading against map points: a least-squares line, extrapolated.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [x, y] : points_rss) {
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double n = static_cast<double>(points_rss.size());
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double map_points = report.Get("tiles", "points");
  report.Set("whole_map_loading", "bytes_per_point", slope * 1024 * 1024);
  report.Set("whole_map_loading", "intercept_mb", (sy - slope * sx) / n);
  report.Set("whole_map_loading", "extrapolated_peak_rss_mb_whole_map",
             (sy - slope * sx) / n + slope * map_points);

  const double ratio = report.Get("short_tiled", "cpu_ms_per_scan_p99") /
                       report.Get("short_whole_corridor_4q", "cpu_ms_per_scan_p99");
  report.Set("targets", "peak_rss_mb (<= 1500)", report.Get("drive_tiled", "peak_rss_mb"));
  report.Set("targets", "first_pose_after_s (<= 5)",
             report.Get("drive_tiled", "first_pose_after_s"));
  report.Set("targets", "cpu_p99_tiled_over_in_memory (<= 1.3)", ratio);
  report.Set("targets", "ate_short_tiled_m", report.Get("short_tiled", "ate_m"));
  report.Set("targets", "ate_short_in_memory_m", report.Get("short_whole_corridor_4q", "ate_m"));
  report.Print(std::cout);
  std::cout << "\nThe machine may be shared: CPU figures are per-process CPU time (per scan: the "
               "scan thread's), RSS is resident memory.\n";
  report.WriteJson(json);
  std::cout << "JSON: " << json << "\n";
  return 0;
}
