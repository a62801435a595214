// `hylo craft --in RAW --out CLEAN [--tiles DIR]`: uniform sampling + moving least squares
// smoothing of a raw map, with normals, and a JSON summary; --tiles also writes the crafted map
// as a tiled map (`hylo tile`).
#include <cstdio>
#include <stdexcept>
#include <string>

#include "commands.h"
#include "hylo/io/cloud_io.h"
#include "hylo/terrain/craft.h"
#include "tile_output.h"

namespace hylo::cli {
namespace {

struct CraftArgs {
  std::string in_path, out_path, json_path;
  std::string tiles;  // also write the crafted map as a tiled map here
  tiles::TileMapOptions tile_options;
  terrain::CraftOptions options;
  bool no_normals = false;
};

io::Json SummaryJson(const CraftArgs& args, const terrain::CraftResult& r) {
  io::Json j = io::Json::object();
  j["in"] = args.in_path;
  j["out"] = args.out_path;
  io::Json& o = j["options"];
  o["voxel_size_m"] = args.options.voxel_size_m;
  o["mls_search_radius_m"] = args.options.mls_search_radius_m;
  o["mls_support_voxel_m"] = args.options.mls_support_voxel_m;
  o["mls_small_radius_m"] = args.options.mls_small_radius_m;
  o["scale_consistency_sigmas"] = args.options.scale_consistency_sigmas;
  o["polynomial_order"] = args.options.polynomial_order;
  o["num_threads"] = args.options.num_threads;
  o["compute_normals"] = args.options.compute_normals;
  io::Json& p = j["points"];
  p["input"] = r.num_input;
  p["non_finite"] = r.num_invalid;
  p["after_sampling"] = r.num_sampled;
  p["dropped_by_mls"] = r.num_dropped_by_mls;
  p["mls_support"] = r.num_support;
  p["small_scale"] = r.num_small_scale;
  p["output"] = r.points_world.size();
  j["seconds"]["sampling"] = r.sampling_seconds;
  j["seconds"]["mls"] = r.mls_seconds;
  j["origin_world"] = io::Json::array({r.origin_world.x(), r.origin_world.y(), r.origin_world.z()});
  return j;
}

void RunCraft(CraftArgs& args) {
  args.options.compute_normals = !args.no_normals;
  std::string why;
  if (!args.options.IsValid(&why)) throw std::invalid_argument(why);
  std::fprintf(stderr, "reading %s\n", args.in_path.c_str());
  io::CloudFile raw = io::ReadCloud(args.in_path);
  std::fprintf(stderr,
               "crafting %zu points: %.3f m sampling, MLS radius %.3f m (small %.3f m, support "
               "voxel %.4f m), order %d, %d thread(s)\n",
               raw.positions.size(), args.options.voxel_size_m, args.options.mls_search_radius_m,
               args.options.mls_small_radius_m, args.options.mls_support_voxel_m,
               args.options.polynomial_order, args.options.num_threads);
  terrain::CraftResult result = terrain::CraftMap(raw.positions, args.options);
  result.num_invalid += raw.dropped_non_finite;
  result.num_input += raw.dropped_non_finite;
  if (!result.ok) throw std::runtime_error(args.in_path + ": " + result.message);
  std::fprintf(stderr,
               "  sampling %.2f s -> %zu points; MLS %.2f s on %zu points -> %zu points (%zu "
               "dropped, %zu at the small radius)\n",
               result.sampling_seconds, result.num_sampled, result.mls_seconds, result.num_support,
               result.points_world.size(), result.num_dropped_by_mls, result.num_small_scale);
  io::CloudFile clean;
  clean.positions = std::move(result.points_world);
  clean.normals = result.normals;
  io::WriteCloud(args.out_path, clean, io::CloudEncoding::kBinary);
  result.points_world = std::move(clean.positions);  // for the summary's counts
  std::fprintf(stderr, "wrote %s\n", args.out_path.c_str());
  io::Json summary = SummaryJson(args, result);
  if (!args.tiles.empty())
    summary["tiles"] = WriteTiles(args.out_path, args.tiles, args.tile_options);
  MaybeWriteJson(args.json_path, summary);
}

}  // namespace

void AddCraftCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "craft", "Clean a raw map: uniform sampling, then moving least squares (with normals)");
  static CraftArgs args;
  cmd->add_option("--in", args.in_path, "raw map (PCD/PLY/LAS)")->required();
  cmd->add_option("--out", args.out_path,
                  "clean map to write (PCD/PLY/LAS), with normals (LAS: as extra bytes "
                  "NormalX/Y/Z)")->required();
  cmd->add_option("--voxel", args.options.voxel_size_m, "uniform sampling voxel edge, m (0 = off)")
      ->capture_default_str();
  cmd->add_option("--radius", args.options.mls_search_radius_m, "MLS search radius, m")
      ->capture_default_str();
  cmd->add_option("--small-radius", args.options.mls_small_radius_m,
                  "smaller MLS radius where the large fit disagrees with it, m (0 = single scale)")
      ->capture_default_str();
  cmd->add_option("--support-voxel", args.options.mls_support_voxel_m,
                  "MLS fits use the input thinned to this voxel, m (0 = all input points; >= "
                  "--voxel = the sampled points only)")
      ->capture_default_str();
  cmd->add_option("--scale-sigmas", args.options.scale_consistency_sigmas,
                  "scale test: confidence interval half-width, standard deviations")
      ->capture_default_str();
  cmd->add_option("--order", args.options.polynomial_order, "MLS polynomial order, 0..3")
      ->capture_default_str();
  cmd->add_option("--threads", args.options.num_threads, "MLS threads")->capture_default_str();
  cmd->add_flag("--no-normals", args.no_normals, "do not write normals");
  cmd->add_option("--json", args.json_path, "write a JSON summary here");
  cmd->add_option("--tiles", args.tiles, "also write the crafted map as a tiled map here");
  AddTileOptions(cmd, &args.tile_options, "tile-");
  cmd->callback([] { RunCraft(args); });
}

}  // namespace hylo::cli
