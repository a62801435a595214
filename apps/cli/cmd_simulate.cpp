// `hylo simulate --out DIR [--seed N] [--session a|b|both] [--duration S] [--lidar M]
// [--lidar-time-offset S]`:
// the substation simulator with ground truth (ROS1 bags, TUM truth, manifests, reference
// cloud, slope grid). Prints the simulation speed of each session.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "commands.h"
#include "hylo/common/time.h"
#include "hylo/io/progress.h"
#include "hylo/sim_io/session_writer.h"

namespace hylo::cli {
namespace {

struct SimulateArgs {
  std::string out_dir, session = "both", lidar = "vlp16", json_path;
  uint64_t seed = 1;
  double duration_s = 0.0;           // 0 = the defaults per session
  double column_deg = 0.0;           // 0 = the default
  double lidar_time_offset_s = 0.0;  // t_imu = t_lidar + offset (lidar.time_offset_s)
  bool skip_site = false;
  sim::SiteOutputOptions site_output;
};

io::Json SessionJson(const sim::SessionSummary& s) {
  io::Json j = io::Json::object();
  j["session"] = sim::ToString(s.session);
  j["duration_s"] = s.duration_s;
  j["imu_samples"] = s.imu_samples;
  j["scans"] = s.scans;
  j["points"] = s.points;
  j["path_length_m"] = s.path_length_m;
  j["max_tilt_deg"] = s.max_tilt_deg;
  j["wall_s"] = s.elapsed_s;
  j["cpu_s"] = s.cpu_s;
  return j;
}

void Run(const SimulateArgs& args) {
  sim::SimulationOptions options;
  options.seed = args.seed;
  if (args.duration_s > 0.0) options.duration_a_s = options.duration_b_s = args.duration_s;
  if (args.column_deg > 0.0) options.lidar.column_deg = args.column_deg;
  // The simulator's IMU clock is true time; its lidar option is the lidar clock minus true
  // time, the opposite sign of the run configuration's t_imu = t_lidar + offset.
  options.lidar.time_offset_ns = -SecondsToNanos(args.lidar_time_offset_s);
  if (!sim::ParseLidarModel(args.lidar, &options.lidar.model)) {
    throw std::runtime_error("--lidar: unknown model '" + args.lidar + "' (vlp16, rs16)");
  }
  std::string why;
  if (!options.IsValid(&why)) throw std::runtime_error(why);
  const sim::Site site = sim::BuildSite(options.seed, options.terrain);
  io::Json summary = io::Json::object();
  summary["out"] = args.out_dir;
  summary["options"] = sim::OptionsToJson(options);
  io::Json sessions = io::Json::array();
  for (const sim::SessionId id : {sim::SessionId::kA, sim::SessionId::kB}) {
    if (args.session != "both" && args.session != sim::ToString(id)) continue;
    std::unique_ptr<io::Progress> progress;
    const sim::SessionSummary s = sim::WriteSession(
        options, site, id, args.out_dir, [&](std::size_t done, std::size_t total) {
          if (!progress) {
            progress = std::make_unique<io::Progress>("session " + sim::ToString(id), total);
          }
          progress->Update(done);
        });
    if (progress) progress->Finish();
    std::printf(
        "session %s: %.1f s simulated, %zu scans, %zu points, %zu IMU samples, "
        "%.1f m driven, max tilt %.1f deg\n",
        sim::ToString(id).c_str(), s.duration_s, s.scans, s.points, s.imu_samples, s.path_length_m,
        s.max_tilt_deg);
    std::printf(
        "session %s speed: %.1f s wall, %.1f s CPU for %.1f s of data "
        "(%.2f x real time on CPU time)\n",
        sim::ToString(id).c_str(), s.elapsed_s, s.cpu_s, s.duration_s,
        s.duration_s / std::max(s.cpu_s, 1e-9));
    sessions.push_back(SessionJson(s));
  }
  summary["sessions"] = sessions;
  if (!args.skip_site) {
    sim::WriteSiteOutputs(options, site, args.site_output, args.out_dir);
    std::printf("site: site_reference.pcd, site_slope.txt, site.json in %s\n",
                args.out_dir.c_str());
  }
  MaybeWriteJson(args.json_path, summary);
}

}  // namespace

void AddSimulateCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "simulate", "Simulate a rough-terrain substation: lidar+IMU bags with ground truth");
  static SimulateArgs args;
  cmd->add_option("--out", args.out_dir, "output directory")->required();
  cmd->add_option("--seed", args.seed, "random seed (same seed, same bytes)");
  cmd->add_option("--session", args.session, "a, b or both")
      ->check(CLI::IsMember({"a", "b", "both"}));
  cmd->add_option("--duration", args.duration_s, "seconds per session (default: A 180 s, B 150 s)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--lidar", args.lidar, "beam table: vlp16 or rs16");
  cmd->add_option("--column-deg", args.column_deg, "azimuth step (default 0.2 deg)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--lidar-time-offset", args.lidar_time_offset_s,
                  "lidar clock behind the IMU's by S seconds: t_imu = t_lidar + S, corrected by "
                  "lidar.time_offset_s: S (default 0)")
      ->check(CLI::Range(-1.0, 1.0));
  cmd->add_option("--reference-spacing", args.site_output.reference_spacing_m,
                  "object sampling of the reference cloud, m");
  cmd->add_flag("--no-site", args.skip_site, "skip the reference cloud and slope grid");
  cmd->add_option("--json", args.json_path, "write a JSON summary (with timings) here");
  cmd->callback([] { Run(args); });
}

}  // namespace hylo::cli
