// `hylo simulate --out DIR [--seed N] [--session a|b|both] [--duration S] [--lidar M]
// [--lidar-time-offset S] [--format ros1|sqlite3|mcap|mcap-zstd|mcap-lz4]`:
// the substation simulator with ground truth (ROS1 bags or ROS 2 recordings, TUM truth,
// manifests, reference cloud, slope grid). Prints the simulation speed of each session.
// `hylo simulate --scenario N --out DIR`: randomized scenario N instead (scenario.h), with
// its sensor sheet and the configuration the sheet gives.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "commands.h"
#include "hylo/common/time.h"
#include "hylo/io/progress.h"
#include "hylo/logs/log_writer.h"
#include "hylo/sim_io/scenario_writer.h"
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
  std::optional<uint64_t> scenario;  // randomized scenario number
  std::string config_dir;            // presets for the scenario's configuration
  std::string format = "ros1";       // the sessions' log format (logs::LogFormat)
};

logs::LogFormat FormatOf(const SimulateArgs& args) {
  logs::LogFormat format = logs::LogFormat::kRos1;
  logs::ParseLogFormat(args.format, &format);  // checked by the option
  return format;
}

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

// Where config/<preset>.yaml is: --config-dir, else ./config, else the source tree's.
std::string PresetDir(const std::string& given) {
  if (!given.empty()) return given;
  if (std::filesystem::exists("config/presets/vlp16.yaml")) return "config/presets";
  return HYLO_PRESET_DIR;
}

// Writes one session's files and prints its figures like the fixed site's sessions.
template <typename Write>
io::Json WriteWithProgress(sim::SessionId id, const Write& write) {
  std::unique_ptr<io::Progress> progress;
  const sim::SessionSummary s = write([&](std::size_t done, std::size_t total) {
    if (!progress) progress = std::make_unique<io::Progress>("session " + sim::ToString(id), total);
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
  return SessionJson(s);
}

void RunScenario(const SimulateArgs& args) {
  sim::Scenario scenario = sim::DrawScenario(*args.scenario);
  if (args.duration_s > 0.0) scenario.max_drive_a_s = scenario.max_drive_b_s = args.duration_s;
  const sim::SensorSheet sheet = sim::SheetOf(scenario);
  const config::RunConfig config = sim::ScenarioRunConfig(sheet, PresetDir(args.config_dir));
  std::printf("scenario %llu: %s\n", static_cast<unsigned long long>(scenario.number),
              scenario.Summary().c_str());
  const sim::Site site = sim::BuildScenarioSite(scenario);
  io::Json summary = io::Json::object();
  summary["out"] = args.out_dir;
  summary["scenario"] = sim::ScenarioToJson(scenario);
  io::Json sessions = io::Json::array();
  for (const sim::SessionId id : {sim::SessionId::kA, sim::SessionId::kB}) {
    if (args.session != "both" && args.session != sim::ToString(id)) continue;
    sessions.push_back(WriteWithProgress(id, [&](const auto& progress) {
      return sim::WriteScenarioSession(scenario, site, id, config, args.out_dir, progress,
                                       FormatOf(args));
    }));
  }
  summary["sessions"] = sessions;
  sim::WriteScenarioSheet(sheet, config, args.out_dir);
  std::printf("sensor_sheet.yaml, config.yaml (config/%s.yaml with the sheet's values) in %s\n",
              sheet.preset.c_str(), args.out_dir.c_str());
  if (!args.skip_site) {
    sim::SimulationOptions options;
    options.seed = scenario.number;
    options.index_cell_m = scenario.index_cell_m;
    sim::WriteSiteOutputs(options, site, args.site_output, args.out_dir);
    std::printf("site: site_reference.pcd, site_slope.txt, site.json in %s\n",
                args.out_dir.c_str());
  }
  MaybeWriteJson(args.json_path, summary);
}

void Run(const SimulateArgs& args) {
  if (args.scenario) return RunScenario(args);
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
    sessions.push_back(WriteWithProgress(id, [&](const auto& progress) {
      return sim::WriteSession(options, site, id, args.out_dir, progress, FormatOf(args));
    }));
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
      "simulate", "Simulate a rough-terrain substation: lidar+IMU logs with ground truth");
  static SimulateArgs args;
  cmd->add_option("--out", args.out_dir, "output directory")->required();
  auto* seed = cmd->add_option("--seed", args.seed, "random seed (same seed, same bytes)");
  cmd->add_option("--session", args.session, "a, b or both")
      ->check(CLI::IsMember({"a", "b", "both"}));
  cmd->add_option("--duration", args.duration_s, "seconds per session (default: A 180 s, B 150 s)")
      ->check(CLI::PositiveNumber);
  auto* lidar = cmd->add_option("--lidar", args.lidar, "beam table: vlp16 or rs16");
  auto* column = cmd->add_option("--column-deg", args.column_deg, "azimuth step (default 0.2 deg)")
                     ->check(CLI::PositiveNumber);
  auto* offset =
      cmd->add_option(
             "--lidar-time-offset", args.lidar_time_offset_s,
             "lidar clock behind the IMU's by S seconds: t_imu = t_lidar + S, corrected by "
             "lidar.time_offset_s: S (default 0)")
          ->check(CLI::Range(-1.0, 1.0));
  cmd->add_option("--reference-spacing", args.site_output.reference_spacing_m,
                  "object sampling of the reference cloud, m");
  cmd->add_flag("--no-site", args.skip_site, "skip the reference cloud and slope grid");
  cmd->add_option("--scenario", args.scenario,
                  "randomized scenario N instead of the fixed site (--duration caps each drive)")
      ->excludes(seed)
      ->excludes(lidar)
      ->excludes(column)
      ->excludes(offset);  // a scenario draws its own clock offset
  cmd->add_option("--config-dir", args.config_dir,
                  "where the scenario's preset config/<preset>.yaml is (default ./config)");
  cmd->add_option("--format", args.format,
                  "session logs: ros1 (.bag), or a ROS 2 recording (rosbag2 directory): sqlite3, "
                  "mcap, mcap-zstd, mcap-lz4")
      ->check(CLI::IsMember({"ros1", "sqlite3", "mcap", "mcap-zstd", "mcap-lz4"}));
  cmd->add_option("--json", args.json_path, "write a JSON summary (with timings) here");
  cmd->callback([] { Run(args); });
}

}  // namespace hylo::cli
