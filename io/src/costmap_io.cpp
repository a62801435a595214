#include "hylo/io/costmap_io.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "hylo/io/atomic_file.h"

namespace hylo::io {
namespace {

using terrain::CellClass;
using terrain::GridGeometry;
using terrain::GridMap;
constexpr double kNoDataValue = -9999.0;

void WriteFile(const std::string& path, const std::string& bytes) {
  WriteFileAtomically(path, bytes);
}

void CheckClasses(const GridMap& grid, const std::vector<CellClass>& classes) {
  if (classes.size() != grid.geometry().NumCells() || !grid.HasLayer(terrain::layers::kCost)) {
    throw std::invalid_argument("costmap: need one class per grid cell and a cost layer");
  }
}

/// Grid cell of image pixel (x, y): images run north to south, grid rows south to north.
std::size_t CellOfPixel(const GridGeometry& g, int x, int y) {
  return g.Index(x, g.height - 1 - y);
}

std::string FormatNumber(double v, const char* format) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, v);
  return buffer;
}

}  // namespace

bool MapServerOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  constexpr double kUnknownOccupancy = 50.0 / 255.0;  // grey 205
  if (!(free_thresh > 0.0 && free_thresh < kUnknownOccupancy)) {
    os << "free_thresh = " << free_thresh << " must be in (0, 50/255) so grey 205 stays unknown";
  } else if (!(occupied_thresh > kUnknownOccupancy && occupied_thresh < 1.0)) {
    os << "occupied_thresh = " << occupied_thresh << " must be in (50/255, 1)";
  }
  if (why) *why = os.str();
  return os.str().empty();
}

uint8_t MapServerPixel(CellClass cell_class, float cost, const MapServerOptions& options) {
  if (cell_class == CellClass::kLethal) return 0;
  if (cell_class == CellClass::kUnknown) return 205;
  // Darkest grey read as free: (255 - p) / 255 < free_thresh.
  const int darkest_free = static_cast<int>(std::floor(255.0 * (1.0 - options.free_thresh))) + 1;
  const double c = std::clamp(static_cast<double>(cost), 0.0, 1.0);
  return static_cast<uint8_t>(254 - std::lround(c * (254 - darkest_free)));
}

void WriteMapServer(const std::string& yaml_path, const GridMap& grid,
                    const std::vector<CellClass>& classes, const MapServerOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("map_server options: " + why);
  CheckClasses(grid, classes);
  const GridGeometry& g = grid.geometry();
  const std::vector<float>& cost = grid.Layer(terrain::layers::kCost);
  const std::filesystem::path pgm_path = std::filesystem::path(yaml_path).replace_extension(".pgm");
  std::string pgm = "P5\n# hylo traversability costmap, " + FormatNumber(g.resolution_m, "%.6g") +
                    " m/pixel\n" + std::to_string(g.width) + " " + std::to_string(g.height) +
                    "\n255\n";
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const std::size_t cell = CellOfPixel(g, x, y);
      pgm.push_back(static_cast<char>(MapServerPixel(classes[cell], cost[cell], options)));
    }
  }
  WriteFile(pgm_path.string(), pgm);
  const Eigen::Vector2d corner = g.CornerWorld();
  std::ostringstream yaml;
  yaml << "# hylo traversability costmap for ROS map_server. Pixels: 0 lethal, 205 unknown,\n"
       << "# 254 free; greys 254..(darkest free) grade the cost of traversable cells.\n"
       << "image: " << pgm_path.filename().string() << "\n"
       << "resolution: " << FormatNumber(g.resolution_m, "%.9g") << "\n"
       << "origin: [" << FormatNumber(corner.x(), "%.6f") << ", "
       << FormatNumber(corner.y(), "%.6f") << ", 0.0]\n"
       << "negate: 0\n"
       << "occupied_thresh: " << FormatNumber(options.occupied_thresh, "%.9g") << "\n"
       << "free_thresh: " << FormatNumber(options.free_thresh, "%.9g") << "\n"
       << "mode: trinary\n";
  WriteFile(yaml_path, yaml.str());
}

void CostColour(CellClass cell_class, float cost, uint8_t rgb[3]) {
  if (cell_class == CellClass::kUnknown) {
    rgb[0] = rgb[1] = rgb[2] = 128;
    return;
  }
  if (cell_class == CellClass::kLethal) {
    rgb[0] = rgb[1] = rgb[2] = 0;
    return;
  }
  // green (0,170,0) -> yellow (255,220,0) at 0.5 -> red (220,0,0) at 1.
  const double c = std::clamp(static_cast<double>(cost), 0.0, 1.0);
  const double t = c < 0.5 ? c / 0.5 : (c - 0.5) / 0.5;
  const std::array<double, 3> from =
      c < 0.5 ? std::array<double, 3>{0, 170, 0} : std::array<double, 3>{255, 220, 0};
  const std::array<double, 3> to =
      c < 0.5 ? std::array<double, 3>{255, 220, 0} : std::array<double, 3>{220, 0, 0};
  for (int i = 0; i < 3; ++i)
    rgb[i] = static_cast<uint8_t>(std::lround(from[i] + t * (to[i] - from[i])));
}

void WriteCostmapPng(const std::string& path, const GridMap& grid,
                     const std::vector<CellClass>& classes) {
  CheckClasses(grid, classes);
  const GridGeometry& g = grid.geometry();
  const std::vector<float>& cost = grid.Layer(terrain::layers::kCost);
  std::vector<uint8_t> rgb(g.NumCells() * 3);
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const std::size_t cell = CellOfPixel(g, x, y);
      CostColour(classes[cell], cost[cell], &rgb[(static_cast<std::size_t>(y) * g.width + x) * 3]);
    }
  }
  WriteFile(path, EncodePngRgb(g.width, g.height, rgb));
}

std::string EncodePngRgb(int width, int height, const std::vector<uint8_t>& rgb) {
  if (width <= 0 || height <= 0 ||
      rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
    throw std::invalid_argument("PNG: need width, height > 0 and width * height * 3 bytes");
  }
  // libpng's simplified API: no setjmp, failures come back as a return value and a message.
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGB;
  std::string png(PNG_IMAGE_PNG_SIZE_MAX(image), '\0');
  png_alloc_size_t size = png.size();
  const bool ok = png_image_write_to_memory(&image, png.data(), &size, /*convert_to_8_bit=*/0,
                                            rgb.data(), /*row_stride=*/0, /*colormap=*/nullptr);
  const std::string message = image.message;
  png_image_free(&image);
  if (!ok) throw std::runtime_error("PNG encoding failed: " + message);
  png.resize(size);
  return png;
}

void WriteAsciiGrid(const std::string& path, const GridMap& grid, const std::string& layer,
                    double value_offset) {
  const GridGeometry& g = grid.geometry();
  const std::vector<float>& values = grid.Layer(layer);
  const Eigen::Vector2d corner = g.CornerWorld();
  std::string text = "ncols " + std::to_string(g.width) + "\nnrows " + std::to_string(g.height) +
                     "\nxllcorner " + FormatNumber(corner.x(), "%.6f") + "\nyllcorner " +
                     FormatNumber(corner.y(), "%.6f") + "\ncellsize " +
                     FormatNumber(g.resolution_m, "%.9g") + "\nNODATA_value " +
                     FormatNumber(kNoDataValue, "%.0f") + "\n";
  for (int row = g.height - 1; row >= 0; --row) {
    for (int col = 0; col < g.width; ++col) {
      const float v = values[g.Index(col, row)];
      if (col > 0) text.push_back(' ');
      text += std::isnan(v) ? FormatNumber(kNoDataValue, "%.0f")
                            : FormatNumber(static_cast<double>(v) + value_offset, "%.8g");
    }
    text.push_back('\n');
  }
  WriteFile(path, text);
}

GridMap ReadAsciiGrid(const std::string& path, const std::string& layer) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::map<std::string, double> header;
  const char* kKeys[] = {"ncols",     "nrows",     "xllcorner", "yllcorner",
                         "xllcenter", "yllcenter", "cellsize",  "nodata_value"};
  while (true) {
    const std::streampos line_start = in.tellg();
    std::string key;
    if (!(in >> key)) break;
    std::transform(key.begin(), key.end(), key.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys)) {
      in.seekg(line_start);  // first value row
      break;
    }
    double value;
    if (!(in >> value)) throw std::runtime_error(path + ": bad value for header key " + key);
    header[key] = value;
  }
  for (const char* key : {"ncols", "nrows", "cellsize"}) {
    if (!header.count(key)) throw std::runtime_error(path + ": missing header key " + key);
  }
  const bool centre = header.count("xllcenter") && header.count("yllcenter");
  if (!centre && !(header.count("xllcorner") && header.count("yllcorner"))) {
    throw std::runtime_error(path + ": missing xllcorner/yllcorner");
  }
  const double ncols = header["ncols"], nrows = header["nrows"];
  if (!(ncols >= 1 && ncols <= 1e8 && nrows >= 1 && nrows <= 1e8) ||
      ncols != std::floor(ncols) || nrows != std::floor(nrows) ||
      !(header["cellsize"] > 0.0 && std::isfinite(header["cellsize"]))) {
    throw std::runtime_error(path + ": ncols, nrows and cellsize must be positive (and ncols, "
                             "nrows whole numbers)");
  }
  // Each value takes at least two bytes (a digit and a separator): a header that promises
  // more values than the file can hold is refused before the grid is allocated.
  const std::streampos values_start = in.tellg();
  in.seekg(0, std::ios::end);
  const double bytes_left = static_cast<double>(in.tellg() - values_start);
  in.seekg(values_start);
  if (2.0 * ncols * nrows > bytes_left + 1.0) {
    throw std::runtime_error(path + ": the header announces " + FormatNumber(ncols * nrows, "%.0f") +
                             " values, more than the file's " + FormatNumber(bytes_left, "%.0f") +
                             " bytes can hold");
  }
  GridGeometry g;
  g.width = static_cast<int>(ncols);
  g.height = static_cast<int>(nrows);
  g.resolution_m = header["cellsize"];
  const double half = centre ? 0.5 * g.resolution_m : 0.0;
  g.origin_world = {header[centre ? "xllcenter" : "xllcorner"] - half,
                    header[centre ? "yllcenter" : "yllcorner"] - half, 0.0};
  if (!g.origin_world.allFinite()) throw std::runtime_error(path + ": the corner is not finite");
  GridMap grid(g);
  std::vector<float>& values = grid.AddLayer(layer, std::nanf(""));
  const bool has_nodata = header.count("nodata_value") > 0;
  for (int row = g.height - 1; row >= 0; --row) {
    for (int col = 0; col < g.width; ++col) {
      double v;
      if (!(in >> v)) {
        throw std::runtime_error(path + ": expected " + std::to_string(g.NumCells()) +
                                 " values, reading row " + std::to_string(g.height - 1 - row) +
                                 " failed");
      }
      if (!(has_nodata && v == header["nodata_value"]))
        values[g.Index(col, row)] = static_cast<float>(v);
    }
  }
  return grid;
}

CostmapLayers ReadCostmapLayers(const std::string& dir) {
  namespace fs = std::filesystem;
  const auto path = [&](const char* layer) {
    return (fs::path(dir) / "layers" / (std::string(layer) + ".asc")).string();
  };
  if (!fs::is_directory(dir)) throw std::runtime_error(dir + ": not a costmap folder (missing)");
  CostmapLayers out;
  out.grid = ReadAsciiGrid(path(terrain::layers::kElevation), terrain::layers::kElevation);
  const GridGeometry& g = out.grid.geometry();
  for (const char* layer : {terrain::layers::kCost, terrain::layers::kClass}) {
    GridMap other = ReadAsciiGrid(path(layer), layer);
    const GridGeometry& o = other.geometry();
    if (o.width != g.width || o.height != g.height ||
        std::abs(o.resolution_m - g.resolution_m) > 1e-9 ||
        (o.origin_world - g.origin_world).norm() > 1e-6) {
      throw std::runtime_error(path(layer) + ": its grid does not lie on " +
                               path(terrain::layers::kElevation) + "'s cells");
    }
    out.grid.AddLayer(layer, 0.f) = other.Layer(layer);
  }
  const std::vector<float>& class_layer = out.grid.Layer(terrain::layers::kClass);
  out.classes.resize(class_layer.size(), CellClass::kUnknown);
  for (std::size_t i = 0; i < class_layer.size(); ++i) {
    const float v = class_layer[i];
    if (std::isnan(v)) continue;
    if (!(v >= 0.f && v < terrain::kNumCellClasses) || v != std::floor(v)) {
      throw std::runtime_error(path(terrain::layers::kClass) + ": value " + FormatNumber(v, "%g") +
                               " at row " + std::to_string(g.height - 1 - g.Row(i)) +
                               " is not a cell class (0 unknown, 1 free, 2 cost, 3 lethal)");
    }
    out.classes[i] = static_cast<CellClass>(static_cast<int>(v));
  }
  return out;
}

std::vector<std::string> WriteTraversabilityFiles(const std::string& dir,
                                                  const terrain::TraversabilityMap& map,
                                                  const MapServerOptions& options) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(fs::path(dir) / "layers", error);
  if (error) throw std::runtime_error(dir + ": cannot create directory (" + error.message() + ")");
  std::vector<std::string> written;
  const std::string yaml = (fs::path(dir) / "costmap.yaml").string();
  WriteMapServer(yaml, map.grid, map.classes, options);
  written.push_back(yaml);
  written.push_back((fs::path(dir) / "costmap.pgm").string());
  written.push_back((fs::path(dir) / "costmap.png").string());
  WriteCostmapPng(written.back(), map.grid, map.classes);
  for (const std::string& layer : map.grid.LayerNames()) {
    const double offset =
        layer == terrain::layers::kElevation ? map.grid.geometry().origin_world.z() : 0.0;
    written.push_back((fs::path(dir) / "layers" / (layer + ".asc")).string());
    WriteAsciiGrid(written.back(), map.grid, layer, offset);
  }
  return written;
}

}  // namespace hylo::io
