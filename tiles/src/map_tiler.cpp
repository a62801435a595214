// Streaming map tiler (map_tiler.h).
#include "hylo/tiles/map_tiler.h"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include "hylo/common/local_origin.h"
#include "hylo/common/option_checks.h"
#include "hylo/common/voxel_key.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/cloud_stream.h"
#include "hylo/registration/voxel_filter.h"
#include "hylo/tiles/tiled_map.h"
#include "hylo/tiles/tiles.h"

namespace hylo::tiles {
namespace {

namespace fs = std::filesystem;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string SpillPath(const std::string& dir, const TileKey& key) {
  return dir + "/" + std::to_string(key.ix) + "_" + std::to_string(key.iy) + ".xyz";
}

// Pass 1: points grouped by tile, appended to one raw float32 x y z file per tile.
class Spills {
 public:
  Spills(std::string dir, std::size_t budget) : dir_(std::move(dir)), budget_(budget) {}

  void Add(const TileKey& key, const Eigen::Vector3f& p) {
    buffers_[key].push_back(p);
    ++counts_[key];
    if (++buffered_ >= budget_) Flush();
  }

  void Flush() {
    for (auto& [key, points] : buffers_) {
      if (points.empty()) continue;
      const std::string path = SpillPath(dir_, key);
      std::ofstream out(path, std::ios::binary | std::ios::app);
      out.write(reinterpret_cast<const char*>(points.data()),
                static_cast<std::streamsize>(points.size() * sizeof(Eigen::Vector3f)));
      if (!out) throw std::runtime_error(path + ": cannot write a spill file (disk full?)");
      PointCloud().swap(points);
    }
    buffered_ = 0;
  }

  PointCloud Read(const TileKey& key) const {
    const std::string path = SpillPath(dir_, key);
    PointCloud points(counts_.at(key));
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(points.data()),
            static_cast<std::streamsize>(points.size() * sizeof(Eigen::Vector3f)));
    if (!in) throw std::runtime_error(path + ": cannot read back a spill file");
    in.close();
    fs::remove(path);
    return points;
  }

  const std::map<TileKey, std::size_t>& counts() const { return counts_; }

 private:
  std::string dir_;
  std::size_t budget_;
  std::size_t buffered_ = 0;
  std::map<TileKey, PointCloud> buffers_;
  std::map<TileKey, std::size_t> counts_;
};

// The lowest point of each voxel: the global localizer's raster keeps the lowest point of
// each of its cells as the ground, which a voxel's nearest-to-centre point would raise.
PointCloud LowestPerVoxel(const PointCloud& points, float voxel_m) {
  struct Hash {
    std::size_t operator()(const VoxelKey& k) const {
      return static_cast<std::size_t>(k.x() * 73856093LL ^ k.y() * 19349663LL ^ k.z() * 83492791LL);
    }
  };
  std::unordered_map<VoxelKey, std::size_t, Hash> lowest;
  PointCloud kept;
  for (const Eigen::Vector3f& p : points) {
    const auto [it, fresh] = lowest.emplace(VoxelOf(p, voxel_m), kept.size());
    if (fresh) {
      kept.push_back(p);
    } else if (p.z() < kept[it->second].z()) {
      kept[it->second] = p;
    }
  }
  return kept;
}

// A tile's file content, and its count and bounds as a reader will see them: PCD tiles hold the
// local float32 points as they are; LAS tiles the world positions, which the reader quantizes to
// the writer's grid and moves back by the origin.
io::CloudFile TileFile(const std::string& path, const PointCloud& points,
                   const Eigen::Vector3d& origin_world, TileFormat format, TiledMapTile* tile) {
  io::CloudFile file;
  file.positions.reserve(points.size());
  for (const Eigen::Vector3f& p : points) {
    file.positions.push_back(p.cast<double>() + (format == TileFormat::kLas ? origin_world
                                                                           : Eigen::Vector3d::Zero()));
  }
  tile->points = points.size();
  tile->min_local = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
  tile->max_local = -tile->min_local;
  const auto bound = [tile](const Eigen::Vector3f& p) {
    tile->min_local = tile->min_local.cwiseMin(p);
    tile->max_local = tile->max_local.cwiseMax(p);
  };
  if (format == TileFormat::kPcd) {
    for (const Eigen::Vector3f& p : points) bound(p);
    return file;
  }
  for (const Eigen::Vector3d& q : io::LasQuantizedPositions(path, file.positions)) {
    bound((q - origin_world).cast<float>());
  }
  return file;
}

// Removes the directory being built unless Release() was called.
class PartialDir {
 public:
  explicit PartialDir(std::string path) : path_(std::move(path)) {
    fs::remove_all(path_);
    fs::create_directories(path_ + "/tiles");
    fs::create_directories(path_ + "/spill");
  }
  ~PartialDir() {
    std::error_code ec;
    if (!released_) fs::remove_all(path_, ec);
  }
  void Release() { released_ = true; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  bool released_ = false;
};

std::string WithoutTrailingSlash(std::string path) {
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return path;
}

void CheckReplaceable(const std::string& out_dir) {
  std::error_code ec;
  if (!fs::exists(out_dir, ec)) return;
  if (IsTiledMap(out_dir) || (fs::is_directory(out_dir, ec) && fs::is_empty(out_dir, ec))) return;
  throw std::runtime_error(out_dir +
                           ": exists and is not a tiled map (no index.json): not "
                           "overwritten");
}

// Moves the finished directory into place (replacing a previous tiled map of that name).
void MoveIntoPlace(PartialDir* partial, const std::string& out_dir) {
  const std::string old = out_dir + ".old-" + std::to_string(::getpid());
  std::error_code ec;
  const bool existed = fs::exists(out_dir, ec);
  if (existed) fs::rename(out_dir, old);
  fs::rename(partial->path(), out_dir);
  partial->Release();
  if (existed) fs::remove_all(old, ec);
}

}  // namespace

bool TileMapOptions::IsValid(std::string* why) const {
  if (!CheckPositive("tile_size_m", tile_size_m, why) ||
      !CheckNonNegative("voxel_m", voxel_m, why) ||
      !CheckNonNegative("overview_voxel_m", overview_voxel_m, why) ||
      !CheckNonNegative("origin_granularity_m", origin_granularity_m, why)) {
    return false;
  }
  if (voxel_m > 0.0 && !IsWholeMultiple(tile_size_m, voxel_m)) {
    return FailOption("tile_size_m", tile_size_m,
                      "must be a whole multiple of voxel_m = " + std::to_string(voxel_m) +
                          " (a voxel must not straddle two tiles)",
                      why);
  }
  if (chunk_points == 0 || spill_buffer_points == 0) {
    return FailOption("chunk_points", static_cast<double>(chunk_points),
                      "chunk_points and spill_buffer_points must be > 0", why);
  }
  return true;
}

TileMapSummary TileMap(const PositionChunks& next, const std::string& source,
                       const std::string& out_dir_in, const TileMapOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("tile options: " + why);
  const std::string out_dir = WithoutTrailingSlash(out_dir_in);
  CheckReplaceable(out_dir);
  PartialDir partial(out_dir + ".partial-" + std::to_string(::getpid()));
  const TileGrid grid(options.tile_size_m);
  const auto voxel = static_cast<float>(options.voxel_m);
  TileMapSummary summary;
  TiledMapIndex index;
  index.tile_size_m = options.tile_size_m;
  index.voxel_m = options.voxel_m;
  index.source = source;

  auto start = std::chrono::steady_clock::now();
  Spills spills(partial.path() + "/spill", options.spill_buffer_points);
  std::vector<Eigen::Vector3d> chunk;
  bool have_origin = false;
  while (next(&chunk)) {
    for (const Eigen::Vector3d& p_world : chunk) {
      if (!have_origin) {
        index.origin_world = options.origin_world
                                 ? *options.origin_world
                                 : ChooseOrigin({p_world}, options.origin_granularity_m);
        index.origin_world += Eigen::Vector3d::Zero();  // -0 (a rounded small negative) is 0
        have_origin = true;
      }
      const Eigen::Vector3f p = (p_world - index.origin_world).cast<float>();
      spills.Add(voxel > 0.f ? grid.KeyOf(p, voxel) : grid.KeyOf(p), p);
    }
    summary.points_read += chunk.size();
  }
  if (summary.points_read == 0) throw std::invalid_argument(source + ": the map has no point");
  spills.Flush();
  summary.split_s = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  std::unique_ptr<io::PcdXyzWriter> overview;
  if (options.overview_voxel_m > 0.0) {
    overview = std::make_unique<io::PcdXyzWriter>(partial.path() + "/overview.pcd");
  }
  index.min_local = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
  index.max_local = -index.min_local;
  for (const auto& [key, count] : spills.counts()) {
    const PointCloud raw = spills.Read(key);
    if (overview) overview->Add(LowestPerVoxel(raw, static_cast<float>(options.overview_voxel_m)));
    TiledMapTile tile;
    tile.ix = key.ix;
    tile.iy = key.iy;
    tile.file = TileFileName(key.ix, key.iy, options.tile_format);
    const std::string path = partial.path() + "/" + tile.file;
    const io::CloudFile file =
        TileFile(path, voxel > 0.f ? registration::UniformSample(raw, voxel) : raw,
                 index.origin_world, options.tile_format, &tile);
    io::WriteCloud(path, file, io::CloudEncoding::kBinary);
    index.min_local = index.min_local.cwiseMin(tile.min_local);
    index.max_local = index.max_local.cwiseMax(tile.max_local);
    index.points += tile.points;
    index.tiles.push_back(tile);
  }
  if (overview) {
    overview->Commit();
    index.overview_file = "overview.pcd";
    index.overview_voxel_m = options.overview_voxel_m;
    index.overview_points = overview->points();
  }
  fs::remove_all(partial.path() + "/spill");
  WriteTiledMapIndex(partial.path(), index);
  MoveIntoPlace(&partial, out_dir);
  summary.tiles_s = SecondsSince(start);
  summary.points_written = index.points;
  summary.tiles = index.tiles.size();
  summary.overview_points = index.overview_points;
  summary.origin_world = index.origin_world;
  return summary;
}

TileMapSummary TileMapFile(const std::string& in_path, const std::string& out_dir,
                           const TileMapOptions& options) {
  std::unique_ptr<io::CloudStream> stream = io::CloudStream::Open(in_path);
  std::size_t non_finite = 0;
  io::CloudFile chunk;
  const PositionChunks next = [&](std::vector<Eigen::Vector3d>* positions) {
    if (!stream->Next(options.chunk_points, &chunk)) return false;
    non_finite += chunk.dropped_non_finite;
    positions->swap(chunk.positions);
    return true;
  };
  TileMapSummary summary = TileMap(next, in_path, out_dir, options);
  summary.non_finite = non_finite;
  return summary;
}

}  // namespace hylo::tiles
