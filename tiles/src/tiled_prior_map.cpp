// Tiled prior maps for a run (tiled_prior_map.h): the tiles as a TileSource read from files, the
// start of localization in them, the added points written back as tiles, and what the loader
// did, for the summary.
#include "hylo/tiles/tiled_prior_map.h"

#include <map>
#include <stdexcept>

#include "hylo/common/local_origin.h"
#include "hylo/registration/voxel_filter.h"
#include "hylo/tiles/map_tiler.h"
#include "hylo/tiles/tile_streamer.h"
#include "hylo/tiles/tiled_map.h"
#include "hylo/tiles/tiled_prior.h"

namespace hylo::tiles {
namespace {

constexpr const char* kAddedLayer = "map_added";

// The tiles of a tiled map directory, and of its added layer (DIR/map_added, hybrid-mode points
// of earlier sessions, in the same grid) when there is one: a tile is the union of both.
class FileTileSource final : public TileSource {
 public:
  FileTileSource(std::string dir, TiledMapIndex index, double thin_voxel_m)
      : dir_(std::move(dir)), index_(std::move(index)), thin_voxel_m_(thin_voxel_m) {
    std::map<TileKey, std::size_t> slots;
    AddLayer(dir_, index_, &slots);
    const std::string added = dir_ + "/" + kAddedLayer;
    if (IsTiledMap(added)) {
      added_index_ = ReadTiledMapIndex(added);
      if (added_index_.tile_size_m != index_.tile_size_m ||
          added_index_.origin_world != index_.origin_world) {
        throw std::runtime_error(TiledMapIndexPath(added) +
                                 ": tile size or origin differ from " +
                                 TiledMapIndexPath(dir_) + " (an added layer must share them)");
      }
      CheckTiledMapFiles(added, added_index_);
      AddLayer(added, added_index_, &slots);
    }
    lookup_ = TileLookup(infos_);
  }

  double tile_size_m() const override { return index_.tile_size_m; }
  const std::vector<TileInfo>& tiles() const override { return infos_; }

  PointCloud Load(const TileKey& key) const override {
    const int i = lookup_.Find(key);
    if (i < 0)
      throw std::runtime_error(dir_ + ": no tile " + std::to_string(key.ix) + " " +
                               std::to_string(key.iy));
    PointCloud points;
    for (const auto& [dir, tile] : parts_[static_cast<std::size_t>(i)]) {
      const PointCloud part = ReadTiledMapTile(dir, index_.origin_world, *tile);
      points.insert(points.end(), part.begin(), part.end());
    }
    return thin_voxel_m_ > 0.0
               ? registration::UniformSample(points, static_cast<float>(thin_voxel_m_))
               : points;
  }

  const TiledMapIndex& index() const { return index_; }
  bool has_added_layer() const { return !added_index_.tiles.empty(); }
  const TiledMapIndex& added_index() const { return added_index_; }

 private:
  void AddLayer(const std::string& dir, const TiledMapIndex& layer,
                std::map<TileKey, std::size_t>* slots) {
    for (const TiledMapTile& t : layer.tiles) {
      const TileKey key{t.ix, t.iy};
      const auto [slot, fresh] = slots->emplace(key, infos_.size());
      if (fresh) {
        TileInfo info;
        info.key = key;
        info.bounds_local.min = t.min_local;
        info.bounds_local.max = t.max_local;
        infos_.push_back(info);
        parts_.emplace_back();
      }
      const std::size_t i = slot->second;
      TileInfo& info = infos_[i];
      info.points += t.points;
      info.bounds_local.min = info.bounds_local.min.cwiseMin(t.min_local);
      info.bounds_local.max = info.bounds_local.max.cwiseMax(t.max_local);
      parts_[i].emplace_back(dir, &t);
    }
  }

  std::string dir_;
  TiledMapIndex index_;
  TiledMapIndex added_index_;
  double thin_voxel_m_;
  std::vector<TileInfo> infos_;
  std::vector<std::vector<std::pair<std::string, const TiledMapTile*>>> parts_;
  TileLookup lookup_;
};

const TiledPrior& TiledPriorOf(const odometry::OdometryPipeline& pipeline) {
  const auto* tiled = dynamic_cast<const TiledPrior*>(pipeline.map().streamed_prior());
  if (tiled == nullptr) throw std::logic_error("the pipeline has no tiled prior");
  return *tiled;
}

const FileTileSource& SourceOf(const odometry::OdometryPipeline& pipeline) {
  return dynamic_cast<const FileTileSource&>(TiledPriorOf(pipeline).streamer().source());
}

}  // namespace

mapping::PriorMap LoadTiledPriorMap(const std::string& dir, const mapping::PriorMapOptions& options,
                                    const std::optional<Eigen::Isometry3d>& T_world_imu_guess,
                                    odometry::OdometryPipeline* pipeline) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(dir + ": PriorMapOptions: " + why);
  TiledMapIndex index = ReadTiledMapIndex(dir);
  CheckTiledMapFiles(dir, index);  // headers only: a broken map fails before any odometry
  // Tiles thinned at the map's resolution or finer are used as they are; coarser maps cannot
  // be made finer (the summary keeps the tiles' voxel).
  const double thin = options.resolution_m > index.voxel_m ? options.resolution_m : 0.0;
  auto source = std::make_shared<FileTileSource>(dir, index, thin);
  TileStreamerOptions streamer_options;
  const odometry::OdometryPipelineOptions& p = pipeline->options();
  streamer_options.load_radius_m =
      options.tile_load_radius_m > 0.0
          ? options.tile_load_radius_m
          : p.preprocess.max_range_m + p.planes.max_neighbor_distance_m;
  streamer_options.unload_margin_m = options.tile_unload_margin_m;
  auto streamer = std::make_shared<TileStreamer>(source, streamer_options);
  const PointCloud overview =
      p.localization.global_enabled ? ReadTiledMapOverview(dir, index) : PointCloud();
  pipeline->SetStreamedPriorMap(
      std::make_shared<TiledPrior>(
          streamer, static_cast<std::size_t>(options.tile_cache_million_points * 1e6)),
      overview);
  // Hybrid mode over a tiled prior keeps what the run's window drops (WriteAddedTiles).
  pipeline->map().KeepWindowedOut(p.localization.update_after_s >= 0.0);
  std::optional<Eigen::Isometry3d> guess_local;
  if (T_world_imu_guess) {
    guess_local = mapping::PoseToLocal(*T_world_imu_guess, index.origin_world);
    // The start registers against the tiles around the guess: wait for them.
    streamer->SetPosition(guess_local->translation().cast<float>());
    streamer->WaitUntilCurrent();
    if (!streamer->error().empty()) throw std::runtime_error(streamer->error());
  }
  pipeline->SetInitialGuess(guess_local);
  mapping::PriorMap prior;
  prior.origin_world = index.origin_world;
  for (const TileInfo& t : source->tiles()) prior.num_kept += t.points;
  prior.num_input = prior.num_kept;
  prior.tiled_dir = dir;
  return prior;
}

io::Json TiledPriorJson(const odometry::OdometryPipeline& pipeline) {
  const FileTileSource& source = SourceOf(pipeline);
  const TiledPrior& tiled = TiledPriorOf(pipeline);
  const TileStreamer& streamer = tiled.streamer();
  const TileStreamerStats s = streamer.stats();
  io::Json j;
  j["tiles"] = source.tiles().size();
  j["tile_size_m"] = source.tile_size_m();
  j["tiles_voxel_m"] = source.index().voxel_m;
  j["added_layer"] = source.has_added_layer();
  j["load_radius_m"] = streamer.options().load_radius_m;
  j["unload_margin_m"] = streamer.options().unload_margin_m;
  j["tiles_loaded"] = s.tiles_loaded;
  j["tiles_unloaded"] = s.tiles_unloaded;
  j["points_loaded"] = s.points_loaded;
  j["max_tiles_held"] = s.max_tiles_held;
  j["max_points_held"] = s.max_points_held;
  j["loader_cpu_s"] = s.load_cpu_s;
  j["tiles_read_on_demand"] = tiled.cache().tiles_loaded();
  return j;
}

std::size_t WriteAddedTiles(const std::string& out_dir, const mapping::PriorMap& prior,
                            const odometry::OdometryPipeline& pipeline, double voxel_m) {
  const FileTileSource& source = SourceOf(pipeline);
  // Earlier sessions' added points (tile by tile, from their files), then this run's: the
  // window's survivors and what it dropped.
  std::vector<PointCloud> parts;
  parts.push_back(pipeline.map().FlattenRun());
  parts.push_back(pipeline.map().windowed_out());
  std::size_t next_tile = 0, next_part = 0;
  const std::string added_dir = prior.tiled_dir + "/" + kAddedLayer;
  const PositionChunks next = [&](std::vector<Eigen::Vector3d>* chunk) {
    PointCloud points;
    if (next_tile < source.added_index().tiles.size()) {
      points = ReadTiledMapTile(added_dir, prior.origin_world,
                                    source.added_index().tiles[next_tile++]);
    } else if (next_part < parts.size()) {
      points = parts[next_part++];
    } else {
      return false;
    }
    *chunk = ToWorld(points, prior.origin_world);
    return true;
  };
  TileMapOptions options;
  options.tile_size_m = source.tile_size_m();
  options.voxel_m = IsWholeMultiple(options.tile_size_m, voxel_m) ? voxel_m : 0.0;
  options.overview_voxel_m = 0.0;
  options.origin_world = prior.origin_world;
  return TileMap(next, "hybrid-mode points added to " + prior.tiled_dir, out_dir, options)
      .points_written;
}

std::unique_ptr<registration::NeighborSearch> TiledPriorSearch(
    const odometry::OdometryPipeline& pipeline, std::size_t cache_points) {
  return std::make_unique<TileCache>(TiledPriorOf(pipeline).streamer().shared_source(),
                                     cache_points);
}

}  // namespace hylo::tiles
