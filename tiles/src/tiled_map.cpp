// The tiled map directory: index.json and its tiles (tiled_map.h).
#include "hylo/tiles/tiled_map.h"

#include <filesystem>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "hylo/io/atomic_file.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/json.h"
#include "hylo/io/text.h"

namespace hylo::tiles {
namespace {

constexpr const char* kFormat = "hylo tiled map";

[[noreturn]] void Fail(const std::string& file, const std::string& why) {
  throw std::runtime_error(file + ": " + why);
}

// Typed access to index.json that names the key path in every error.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  const io::Json& At(const io::Json& object, const std::string& key, const std::string& path) const {
    if (!object.is_object() || !object.contains(key)) Fail(file_, "missing key '" + path + "'");
    return object.at(key);
  }
  double Number(const io::Json& object, const std::string& key, const std::string& path) const {
    const io::Json& value = At(object, key, path);
    if (!value.is_number()) Fail(file_, "key '" + path + "' is not a number");
    return value.get<double>();
  }
  std::size_t Count(const io::Json& object, const std::string& key, const std::string& path) const {
    const io::Json& value = At(object, key, path);
    if (!value.is_number_unsigned() && !(value.is_number_integer() && value.get<int64_t>() >= 0)) {
      Fail(file_, "key '" + path + "' is not a count");
    }
    return value.get<std::size_t>();
  }
  int32_t Int(const io::Json& object, const std::string& key, const std::string& path) const {
    const io::Json& value = At(object, key, path);
    if (!value.is_number_integer()) Fail(file_, "key '" + path + "' is not an integer");
    return value.get<int32_t>();
  }
  std::string Text(const io::Json& object, const std::string& key, const std::string& path) const {
    const io::Json& value = At(object, key, path);
    if (!value.is_string()) Fail(file_, "key '" + path + "' is not a string");
    return value.get<std::string>();
  }
  Eigen::Vector3d Vector(const io::Json& object, const std::string& key,
                         const std::string& path) const {
    const io::Json& value = At(object, key, path);
    if (!value.is_array() || value.size() != 3) Fail(file_, "key '" + path + "' is not [x, y, z]");
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) {
      if (!value[k].is_number()) Fail(file_, "key '" + path + "' is not [x, y, z]");
      v[k] = value[k].get<double>();
    }
    if (!v.allFinite()) Fail(file_, "key '" + path + "' is not finite");
    return v;
  }
  // A path inside the map directory, relative and without "..".
  std::string RelativeFile(const io::Json& object, const std::string& key,
                           const std::string& path) const {
    const std::string file = Text(object, key, path);
    const std::filesystem::path p(file);
    bool up = false;
    for (const auto& part : p) up = up || part == "..";
    if (file.empty() || p.is_absolute() || up) {
      Fail(file_, "key '" + path + "' = '" + file + "' is not a file inside the map directory");
    }
    return file;
  }

 private:
  std::string file_;
};

io::Json Vec(const Eigen::Vector3d& v) { return io::Json::array({v.x(), v.y(), v.z()}); }
io::Json Vec(const Eigen::Vector3f& v) { return Vec(Eigen::Vector3d(v.cast<double>())); }

TiledMapTile ReadTile(const Reader& r, const io::Json& t, const std::string& path,
                      const std::string& index_file) {
  TiledMapTile tile;
  tile.ix = r.Int(t, "ix", path + ".ix");
  tile.iy = r.Int(t, "iy", path + ".iy");
  tile.file = r.RelativeFile(t, "file", path + ".file");
  tile.points = r.Count(t, "points", path + ".points");
  tile.min_local = r.Vector(t, "min", path + ".min").cast<float>();
  tile.max_local = r.Vector(t, "max", path + ".max").cast<float>();
  if ((tile.min_local.array() > tile.max_local.array()).any()) {
    Fail(index_file, "key '" + path + "': min is above max");
  }
  return tile;
}

std::string JoinPath(const std::string& dir, const std::string& file) {
  return (std::filesystem::path(dir) / file).string();
}

}  // namespace

std::string TiledMapIndexPath(const std::string& dir) { return JoinPath(dir, "index.json"); }

bool IsTiledMap(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_directory(path, ec) &&
         std::filesystem::is_regular_file(TiledMapIndexPath(path), ec);
}

std::string TileFileName(int32_t ix, int32_t iy, TileFormat format) {
  return "tiles/" + std::to_string(ix) + "_" + std::to_string(iy) +
         (format == TileFormat::kLas ? ".las" : ".pcd");
}

bool IsWorldFrameTile(const std::string& file) {
  return io::ToLower(std::filesystem::path(file).extension().string()) == ".las";
}

TiledMapIndex ReadTiledMapIndex(const std::string& dir) {
  const std::string file = TiledMapIndexPath(dir);
  if (!std::filesystem::is_directory(dir)) Fail(dir, "not a directory (a tiled map is one)");
  const io::Json json = io::ReadJsonFile(file);
  const Reader r(file);
  if (r.Text(json, "format", "format") != kFormat) {
    Fail(file, "key 'format' is not '" + std::string(kFormat) + "'");
  }
  TiledMapIndex index;
  index.version = r.Int(json, "version", "version");
  if (index.version < 1 || index.version > TiledMapIndex::kVersion) {
    Fail(file, "version " + std::to_string(index.version) +
                   " is not readable here (this hylo "
                   "reads version " +
                   std::to_string(TiledMapIndex::kVersion) + ")");
  }
  index.tile_size_m = r.Number(json, "tile_size_m", "tile_size_m");
  index.voxel_m = r.Number(json, "voxel_m", "voxel_m");
  if (!(index.tile_size_m > 0.0) || !(index.voxel_m >= 0.0)) {
    Fail(file, "tile_size_m must be > 0 and voxel_m >= 0");
  }
  index.origin_world = r.Vector(json, "origin_world", "origin_world");
  index.source = r.Text(json, "source", "source");
  index.points = r.Count(json, "points", "points");
  const io::Json& bounds = r.At(json, "bounds_local", "bounds_local");
  index.min_local = r.Vector(bounds, "min", "bounds_local.min").cast<float>();
  index.max_local = r.Vector(bounds, "max", "bounds_local.max").cast<float>();
  const io::Json& overview = r.At(json, "overview", "overview");
  if (!overview.is_null()) {
    index.overview_file = r.RelativeFile(overview, "file", "overview.file");
    index.overview_voxel_m = r.Number(overview, "voxel_m", "overview.voxel_m");
    index.overview_points = r.Count(overview, "points", "overview.points");
  }
  const io::Json& tiles = r.At(json, "tiles", "tiles");
  if (!tiles.is_array()) Fail(file, "key 'tiles' is not an array");
  std::set<std::pair<int32_t, int32_t>> keys;
  std::size_t sum = 0;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const std::string path = "tiles[" + std::to_string(i) + "]";
    index.tiles.push_back(ReadTile(r, tiles[i], path, file));
    const TiledMapTile& t = index.tiles.back();
    if (!keys.insert({t.ix, t.iy}).second) {
      Fail(file, "key '" + path + "': tile " + std::to_string(t.ix) + " " + std::to_string(t.iy) +
                     " is listed twice");
    }
    sum += t.points;
  }
  if (sum != index.points) {
    Fail(file, "the tiles hold " + std::to_string(sum) + " points, key 'points' says " +
                   std::to_string(index.points));
  }
  return index;
}

void WriteTiledMapIndex(const std::string& dir, const TiledMapIndex& index) {
  io::Json j;
  j["format"] = kFormat;
  j["version"] = index.version;
  j["tile_size_m"] = index.tile_size_m;
  j["voxel_m"] = index.voxel_m;
  j["origin_world"] = Vec(index.origin_world);
  j["frame"] =
      "PCD tile and overview points are local (world = point + origin_world); LAS tiles are "
      "world";
  j["source"] = index.source;
  j["points"] = index.points;
  j["bounds_local"] = {{"min", Vec(index.min_local)}, {"max", Vec(index.max_local)}};
  j["overview"] = nullptr;
  if (!index.overview_file.empty()) {
    j["overview"] = {{"file", index.overview_file},
                     {"voxel_m", index.overview_voxel_m},
                     {"points", index.overview_points}};
  }
  j["tiles"] = io::Json::array();
  for (const TiledMapTile& t : index.tiles) {
    io::Json tile;
    tile["ix"] = t.ix;
    tile["iy"] = t.iy;
    tile["file"] = t.file;
    tile["points"] = t.points;
    tile["min"] = Vec(t.min_local);
    tile["max"] = Vec(t.max_local);
    j["tiles"].push_back(tile);
  }
  io::WriteFileAtomically(TiledMapIndexPath(dir), io::DumpJson(j) + "\n");
}

void CheckTiledMapFiles(const std::string& dir, const TiledMapIndex& index) {
  for (const TiledMapTile& t : index.tiles) {
    const std::string path = JoinPath(dir, t.file);
    if (!std::filesystem::is_regular_file(path)) {
      Fail(path, "missing (" + TiledMapIndexPath(dir) + " lists it)");
    }
    const io::CloudFileInfo info = io::ReadCloudInfo(path);
    if (info.points != t.points) {
      Fail(path, std::to_string(info.points) + " points, " + TiledMapIndexPath(dir) + " says " +
                     std::to_string(t.points) + ": the index does not match its tiles");
    }
  }
}

PointCloud ReadTiledMapTile(const std::string& dir, const Eigen::Vector3d& origin_world,
                            const TiledMapTile& tile) {
  const std::string path = JoinPath(dir, tile.file);
  const io::CloudFile cloud = io::ReadCloud(path);
  const Eigen::Vector3d shift = IsWorldFrameTile(tile.file) ? origin_world : Eigen::Vector3d::Zero();
  if (cloud.positions.size() != tile.points || cloud.dropped_non_finite > 0) {
    Fail(path, std::to_string(cloud.positions.size()) + " finite points, " +
                   TiledMapIndexPath(dir) + " says " + std::to_string(tile.points) +
                   ": the index does not match its tiles");
  }
  PointCloud points;
  points.reserve(cloud.positions.size());
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
  Eigen::Vector3f hi = -lo;
  for (const Eigen::Vector3d& p : cloud.positions) {
    points.push_back((p - shift).cast<float>());
    lo = lo.cwiseMin(points.back());
    hi = hi.cwiseMax(points.back());
  }
  if (!points.empty() && (lo != tile.min_local || hi != tile.max_local)) {
    std::ostringstream os;
    os << "points span [" << lo.transpose() << "] .. [" << hi.transpose() << "], "
       << TiledMapIndexPath(dir) << " says [" << tile.min_local.transpose() << "] .. ["
       << tile.max_local.transpose() << "]: the index does not match its tiles";
    Fail(path, os.str());
  }
  return points;
}

PointCloud ReadTiledMapOverview(const std::string& dir, const TiledMapIndex& index) {
  if (index.overview_file.empty()) return {};
  const std::string path = JoinPath(dir, index.overview_file);
  const io::CloudFile cloud = io::ReadCloud(path);
  if (cloud.positions.size() != index.overview_points) {
    Fail(path, std::to_string(cloud.positions.size()) + " points, " + TiledMapIndexPath(dir) +
                   " says " + std::to_string(index.overview_points));
  }
  PointCloud points;
  points.reserve(cloud.positions.size());
  for (const Eigen::Vector3d& p : cloud.positions) points.push_back(p.cast<float>());
  return points;
}

}  // namespace hylo::tiles
