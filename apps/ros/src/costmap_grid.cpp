#include "costmap_grid.h"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace hylo::rosnode {
namespace {

struct MapServerYaml {
  std::string image;
  double resolution_m = 0.0;
  double origin[3] = {0.0, 0.0, 0.0};
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  std::string mode = "trinary";
};

struct GreyImage {
  int width = 0, height = 0;
  std::vector<uint8_t> pixels;  ///< top row first, as stored
};

[[noreturn]] void Fail(const std::string& path, const std::string& why) {
  throw std::runtime_error("map '" + path + "': " + why);
}

MapServerYaml ReadYaml(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const std::exception& e) {
    Fail(path, std::string("cannot read YAML (") + e.what() + ")");
  }
  MapServerYaml y;
  try {
    if (!root["image"] || !root["resolution"] || !root["origin"]) {
      Fail(path, "needs the keys image, resolution and origin");
    }
    y.image = root["image"].as<std::string>();
    y.resolution_m = root["resolution"].as<double>();
    const YAML::Node origin = root["origin"];
    if (!origin.IsSequence() || origin.size() != 3) Fail(path, "origin must be [x, y, yaw]");
    for (int i = 0; i < 3; ++i) y.origin[i] = origin[i].as<double>();
    if (root["negate"]) y.negate = root["negate"].as<int>() != 0;
    if (root["occupied_thresh"]) y.occupied_thresh = root["occupied_thresh"].as<double>();
    if (root["free_thresh"]) y.free_thresh = root["free_thresh"].as<double>();
    if (root["mode"]) y.mode = root["mode"].as<std::string>();
  } catch (const YAML::Exception& e) {
    Fail(path, std::string("bad value (") + e.what() + ")");
  }
  if (!(y.resolution_m > 0.0)) Fail(path, "resolution must be > 0");
  if (y.mode != "trinary" && y.mode != "scale" && y.mode != "raw") {
    Fail(path, "mode '" + y.mode + "': expected trinary, scale or raw");
  }
  if (!(y.free_thresh < y.occupied_thresh)) Fail(path, "free_thresh must be < occupied_thresh");
  return y;
}

/// Next header token of a PGM, skipping whitespace and # comments.
std::string PgmToken(const std::string& bytes, std::size_t* pos) {
  while (*pos < bytes.size()) {
    const char c = bytes[*pos];
    if (c == '#') {
      while (*pos < bytes.size() && bytes[*pos] != '\n') ++*pos;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++*pos;
    } else {
      break;
    }
  }
  const std::size_t start = *pos;
  while (*pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[*pos]))) ++*pos;
  return bytes.substr(start, *pos - start);
}

GreyImage ReadPgm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) Fail(path, "cannot open the image");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t pos = 0;
  const std::string magic = PgmToken(bytes, &pos);
  if (magic != "P5" && magic != "P2") Fail(path, "not a PGM (P5/P2) image; magic '" + magic + "'");
  GreyImage image;
  int max_value = 0;
  try {
    image.width = std::stoi(PgmToken(bytes, &pos));
    image.height = std::stoi(PgmToken(bytes, &pos));
    max_value = std::stoi(PgmToken(bytes, &pos));
  } catch (const std::exception&) {
    Fail(path, "malformed PGM header");
  }
  if (image.width <= 0 || image.height <= 0 || max_value <= 0 || max_value > 255) {
    Fail(path, "unsupported PGM size or max value (8-bit only)");
  }
  const std::size_t count = static_cast<std::size_t>(image.width) * image.height;
  image.pixels.resize(count);
  if (magic == "P5") {
    ++pos;  // the single whitespace after the max value
    if (bytes.size() < pos + count) Fail(path, "PGM data truncated");
    for (std::size_t i = 0; i < count; ++i) image.pixels[i] = static_cast<uint8_t>(bytes[pos + i]);
  } else {
    for (std::size_t i = 0; i < count; ++i) {
      const std::string token = PgmToken(bytes, &pos);
      if (token.empty()) Fail(path, "PGM data truncated");
      image.pixels[i] = static_cast<uint8_t>(std::stoi(token));
    }
  }
  // Rescale to 0..255 so the thresholds mean the same for any max value.
  if (max_value != 255) {
    for (uint8_t& p : image.pixels) p = static_cast<uint8_t>(p * 255 / max_value);
  }
  return image;
}

int8_t CellValue(uint8_t pixel, const MapServerYaml& y) {
  if (y.mode == "raw") return static_cast<int8_t>(pixel);
  const double occupancy = y.negate ? pixel / 255.0 : (255 - pixel) / 255.0;
  if (occupancy > y.occupied_thresh) return 100;
  if (occupancy < y.free_thresh) return 0;
  if (y.mode == "trinary") return -1;
  return static_cast<int8_t>(99.0 * (occupancy - y.free_thresh) /
                             (y.occupied_thresh - y.free_thresh));
}

}  // namespace

OccupancyGridData ReadMapServerMap(const std::string& yaml_path) {
  const MapServerYaml y = ReadYaml(yaml_path);
  std::filesystem::path image_path(y.image);
  if (image_path.is_relative()) {
    image_path = std::filesystem::path(yaml_path).parent_path() / y.image;
  }
  const GreyImage image = ReadPgm(image_path.string());
  OccupancyGridData grid;
  grid.resolution_m = y.resolution_m;
  grid.width = image.width;
  grid.height = image.height;
  grid.origin_x_m = y.origin[0];
  grid.origin_y_m = y.origin[1];
  grid.origin_yaw_rad = y.origin[2];
  grid.cells.resize(image.pixels.size());
  // Image rows run north to south; grid row 0 is the southern (lowest y) one.
  for (int row = 0; row < grid.height; ++row) {
    const int image_row = grid.height - 1 - row;
    for (int col = 0; col < grid.width; ++col) {
      grid.cells[static_cast<std::size_t>(row) * grid.width + col] =
          CellValue(image.pixels[static_cast<std::size_t>(image_row) * grid.width + col], y);
    }
  }
  return grid;
}

}  // namespace hylo::rosnode
