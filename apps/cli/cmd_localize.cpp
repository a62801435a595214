// `hylo localize --log LOG --map MAP --config C [--guess G] [--update-after S] --out DIR`:
// localization in a prior map (Alamanos et al., Sec. III). The first static scans are
// registered to the map by the ICP initializer from the guess (accepted only under the
// fitness threshold); without a guess, or when it is rejected, the global localizer searches
// the whole map (localization.global_enabled). No accepted start: a clear error and no
// odometry. Then the configured back-end tracks
// against the prior, in hybrid mode extending the map after localization.update_after_s.
// Writes the files of hylo/run/run_log.h, with the paper's cloud-to-cloud metric and every
// initialization/loss/relocalization event in summary.json.

#include <cmath>
#include <cstdio>

#include "commands.h"
#include "hylo/config/run_config.h"
#include "hylo/localization/pose_guess.h"
#include "hylo/run/run_log.h"

namespace hylo::cli {
namespace {

struct LocalizeArgs {
  std::string log, map, config, guess, out, json;
  double update_after_s = std::nan("");  // NaN = as configured
  double c2c_max_distance_m = 0.5;
};

void RunLocalize(const LocalizeArgs& args) {
  run::RunRequest request;
  request.log = args.log;
  request.prior_map = args.map;
  request.config = config::LoadRunConfig(args.config);
  if (!std::isnan(args.update_after_s)) {
    request.config.pipeline.localization.update_after_s = args.update_after_s;
    std::string why;
    if (!request.config.pipeline.localization.IsValid(&why)) {
      throw std::invalid_argument("--update-after: " + why);
    }
  }
  const std::string guess = args.guess.empty() ? request.config.initial_guess : args.guess;
  if (guess.empty() && !request.config.pipeline.localization.global_enabled) {
    throw std::invalid_argument("no initial guess and localization.global_enabled is false: "
                                "pass --guess \"x y z roll pitch yaw\" or set "
                                "localization.initial_guess in " + args.config);
  }
  if (!guess.empty()) request.guess_world_imu = localization::ParsePoseGuess(guess);
  request.config.initial_guess = guess;  // saved with the effective config
  request.c2c_max_distance_m = args.c2c_max_distance_m;
  request.out_dir = args.out;
  request.label = "localize";
  const run::RunResult result = run::RunLog(request);
  MaybeWriteJson(args.json, result.summary);
  const io::Json& s = result.summary;
  std::printf(
      "%s: %zu scans, path %.1f m, %zu events, c2c mean %.3f m std %.3f m, "
      "%.2f ms/scan median, %.2f p99\n",
      s.at("mode").get_ref<const std::string&>().c_str(), result.trajectory.size(),
      io::NumberAt(s, "path_length_m"), s.at("events").size(), io::NumberAt(s, "c2c.mean_m"),
      io::NumberAt(s, "c2c.std_m"), io::NumberAt(s, "ms_per_scan_median"),
      io::NumberAt(s, "ms_per_scan_p99"));
  const std::string calibration = run::OnlineCalibrationLine(s);
  if (!calibration.empty()) std::printf("%s\n", calibration.c_str());
}

}  // namespace

void AddLocalizeCommand(CLI::App& root) {
  auto args = std::make_shared<LocalizeArgs>();
  CLI::App* cmd = root.add_subcommand("localize", "Localization in a prior map (+ hybrid mode)");
  cmd->add_option("--log", args->log, "the log: a ROS1 bag, a ROS 2 recording (rosbag2 directory or .mcap) or a scan folder")->required();
  cmd->add_option("--map", args->map,
                  "prior map: PCD/PLY/LAS (world frame), or a tiled map directory (hylo tile), "
                  "streamed around the vehicle")
      ->required();
  cmd->add_option("--config", args->config, "run configuration (YAML)")->required();
  cmd->add_option("--guess", args->guess,
                  "T_world_imu at the start: \"x y z roll pitch yaw\" (m, deg) or 16 numbers; "
                  "without one the whole map is searched");
  cmd->add_option("--update-after", args->update_after_s,
                  "hybrid mode: add scans to the map after this many seconds (-1 = never)");
  cmd->add_option("--c2c-max-dist", args->c2c_max_distance_m,
                  "outlier threshold of the cloud-to-cloud metric, m")->check(CLI::PositiveNumber);
  cmd->add_option("--out", args->out, "output directory")->required();
  cmd->add_option("--json", args->json, "also write the summary to this JSON file");
  cmd->callback([args]() { RunLocalize(*args); });
}

}  // namespace hylo::cli
