// `hylo tile --in MAP --out DIR [--tile-size 50] [--voxel 0.1] [--tile-format pcd|las]`: cuts a
// map (PCD/PLY/KITTI .bin/LAS, any size: it is read in chunks, io/map_tiler.h) into a tiled map
// directory that `hylo localize --map DIR` streams around the vehicle. Prints the throughput and
// peak memory; the `--tiles DIR` option of `hylo map` and `hylo craft` writes the same from
// their outputs.

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <map>

#include "commands.h"
#include "hylo/tiles/map_tiler.h"
#include "tile_output.h"

namespace hylo::cli {

void AddTileOptions(CLI::App* cmd, tiles::TileMapOptions* options, const std::string& prefix) {
  cmd->add_option("--tile-size", options->tile_size_m,
                  "tile edge, m (a whole number of --" + prefix + "voxel)")
      ->capture_default_str();
  cmd->add_option("--" + prefix + "voxel", options->voxel_m,
                  "thin the tiles at this voxel (uniform sampling, as a prior map), m; 0 = keep "
                  "every point")
      ->capture_default_str();
  cmd->add_option("--" + prefix + "overview-voxel", options->overview_voxel_m,
                  "overview for the global localizer (lowest point per voxel), m; 0 = none")
      ->capture_default_str();
  const std::map<std::string, tiles::TileFormat> formats = {{"pcd", tiles::TileFormat::kPcd},
                                                         {"las", tiles::TileFormat::kLas}};
  cmd->add_option("--tile-format", options->tile_format,
                  "tile files: pcd (float32, the map's local frame) or las (LAS 1.4 in the world "
                  "frame, 0.1 mm, for survey software)")
      ->transform(CLI::CheckedTransformer(formats, CLI::ignore_case))
      ->default_str("pcd");
}

io::Json WriteTiles(const std::string& in_path, const std::string& out_dir,
                    const tiles::TileMapOptions& options) {
  std::fprintf(stderr, "tiling %s into %s (%.1f m tiles)\n", in_path.c_str(), out_dir.c_str(),
               options.tile_size_m);
  const auto start = std::chrono::steady_clock::now();
  const tiles::TileMapSummary s = tiles::TileMapFile(in_path, out_dir, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  io::Json j;
  j["in"] = in_path;
  j["out"] = out_dir;
  j["tile_size_m"] = options.tile_size_m;
  j["voxel_m"] = options.voxel_m;
  j["tile_format"] = options.tile_format == tiles::TileFormat::kLas ? "las" : "pcd";
  j["points_read"] = s.points_read;
  j["non_finite"] = s.non_finite;
  j["points_written"] = s.points_written;
  j["tiles"] = s.tiles;
  j["overview_points"] = s.overview_points;
  j["origin_world"] = io::Json::array({s.origin_world.x(), s.origin_world.y(), s.origin_world.z()});
  j["seconds"] = seconds;
  j["split_s"] = s.split_s;
  j["tiles_s"] = s.tiles_s;
  j["points_per_s"] = seconds > 0.0 ? s.points_read / seconds : 0.0;
  // CPU time too: on a shared machine the wall time says more about the neighbours.
  const double cpu_s = usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
                       1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  j["cpu_s"] = cpu_s;
  j["points_per_cpu_s"] = cpu_s > 0.0 ? s.points_read / cpu_s : 0.0;
  j["peak_memory_mb"] = usage.ru_maxrss / 1024.0;
  std::fprintf(stderr,
               "%zu points read (%zu non-finite dropped), %zu written in %zu tiles, overview %zu "
               "points; %.1f s (%.2f M points/s), peak memory %.0f MB\n",
               s.points_read, s.non_finite, s.points_written, s.tiles, s.overview_points, seconds,
               seconds > 0.0 ? 1e-6 * s.points_read / seconds : 0.0, usage.ru_maxrss / 1024.0);
  return j;
}

namespace {

struct TileArgs {
  std::string in, out, json;
  tiles::TileMapOptions options;
};

}  // namespace

void AddTileCommand(CLI::App& root) {
  auto args = std::make_shared<TileArgs>();
  CLI::App* cmd = root.add_subcommand(
      "tile", "Cut a map of any size into tiles that localization streams around the vehicle");
  cmd->add_option("--in", args->in, "map (PCD/PLY/KITTI .bin/LAS, world frame)")->required();
  cmd->add_option("--out", args->out, "tiled map directory to write (replaced if a tiled map)")
      ->required();
  AddTileOptions(cmd, &args->options, "");
  cmd->add_option("--json", args->json, "also write the summary to this JSON file");
  cmd->callback(
      [args]() { MaybeWriteJson(args->json, WriteTiles(args->in, args->out, args->options)); });
}

}  // namespace hylo::cli
