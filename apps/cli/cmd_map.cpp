// `hylo map --log LOG --config C --out DIR [--json PATH]`: SLAM from scratch with the
// configured back-end. Writes the trajectory of the IMU frame in the map frame (TUM), the
// odometry stream, the map (PCD; and map_dense.pcd, every registered scan at
// output.dense_map_voxel_m, the input of offline crafting), per-scan timing (CSV), the
// effective configuration and a JSON summary (hylo/run/run_log.h); with --tiles DIR also the
// map as a tiled map (`hylo tile`).

#include <cstdio>

#include "commands.h"
#include "hylo/config/run_config.h"
#include "hylo/run/run_log.h"
#include "tile_output.h"

namespace hylo::cli {
namespace {

struct MapArgs {
  std::string log, config, out, json;
  std::string tiles;  // also write the map as a tiled map here
  tiles::TileMapOptions tile_options;
};

void RunMap(const MapArgs& args) {
  run::RunRequest request;
  request.log = args.log;
  request.config = config::LoadRunConfig(args.config);
  request.out_dir = args.out;
  request.label = "map";
  const run::RunResult result = run::RunLog(request);
  io::Json summary = result.summary;
  if (!args.tiles.empty()) {
    // The dense map when there is one (what crafting and localization use), else the tree's.
    const bool dense = request.config.pipeline.output.dense_map_voxel_m > 0.0;
    summary["tiles"] = WriteTiles(args.out + (dense ? "/map_dense.pcd" : "/map.pcd"), args.tiles,
                                  args.tile_options);
  }
  MaybeWriteJson(args.json, summary);
  std::printf("%zu scans, path %.1f m, map %zu points, %.2f ms/scan median, %.2f p99\n",
              result.trajectory.size(), io::NumberAt(result.summary, "path_length_m"),
              result.summary.at("map_points").get<std::size_t>(),
              io::NumberAt(result.summary, "ms_per_scan_median"),
              io::NumberAt(result.summary, "ms_per_scan_p99"));
  const std::string calibration = run::OnlineCalibrationLine(result.summary);
  if (!calibration.empty()) std::printf("%s\n", calibration.c_str());
}

}  // namespace

void AddMapCommand(CLI::App& root) {
  auto args = std::make_shared<MapArgs>();
  CLI::App* cmd = root.add_subcommand("map", "SLAM from scratch: trajectory, map, timing");
  cmd->add_option("--log", args->log, "the log: a ROS1 bag, a ROS 2 recording (rosbag2 directory or .mcap) or a scan folder")->required();
  cmd->add_option("--config", args->config, "run configuration (YAML)")->required();
  cmd->add_option("--out", args->out, "output directory")->required();
  cmd->add_option("--json", args->json, "also write the summary to this JSON file");
  cmd->add_option("--tiles", args->tiles,
                  "also write the map (map_dense.pcd, else map.pcd) as a tiled map here");
  AddTileOptions(cmd, &args->tile_options, "tile-");
  cmd->callback([args]() { RunMap(*args); });
}

}  // namespace hylo::cli
