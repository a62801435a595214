#pragma once
// Costmap and grid-layer files for planners, people and GIS tools:
//  - ROS map_server map: an 8-bit PGM + YAML (image, resolution, origin, negate,
//    occupied_thresh, free_thresh, mode). map_server reads a pixel p as occupancy
//    (255 - p) / 255 (negate 0) and, in trinary mode, > occupied_thresh -> occupied,
//    < free_thresh -> free, otherwise unknown. Written: lethal 0 (occupied), unknown 205
//    (map_saver's value, read as unknown), free and cost cells 254 down to the darkest grey
//    still read as free, graded by cost (traversable at a cost is still traversable; the grade
//    stays visible and `mode: raw` recovers it).
//  - A coloured PNG for people: unknown grey (128,128,128), lethal black, free/cost from green
//    (cost 0) through yellow (0.5) to red (cost 1). RGB, 8 bit, encoded by libpng.
//  - Each float layer as an ESRI ASCII grid (.asc, read by GDAL/QGIS): a six-line header
//      ncols W / nrows H / xllcorner X / yllcorner Y / cellsize R / NODATA_value -9999
//    (X, Y = world position of the grid's lower-left corner, m), then H lines of W values,
//    the first line being the northern (highest y) row.
// Image rows likewise run north to south; the grid's row 0 (lowest y) is the last line.

#include <cstdint>
#include <string>
#include <vector>

#include "hylo/terrain/grid_map.h"
#include "hylo/terrain/traversability.h"

namespace hylo::io {

struct MapServerOptions {
  double occupied_thresh = 0.65;  ///< YAML occupied_thresh: occupancy above -> occupied, 0..1
  double free_thresh = 0.196;     ///< YAML free_thresh: occupancy below -> free, 0..1; must
                                  ///< stay below 50/255 so the unknown grey 205 is not free

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

/// The PGM grey of a cell for map_server (see the file comment).
uint8_t MapServerPixel(terrain::CellClass cell_class, float cost, const MapServerOptions& options);

/// Writes `yaml_path` and the PGM beside it (same name, .pgm; referenced relatively). The
/// YAML origin is the world position of the lower-left pixel (yaw 0). Throws
/// std::runtime_error naming the file when it cannot be written, std::invalid_argument for
/// invalid options or a class/cost size that does not match the grid.
void WriteMapServer(const std::string& yaml_path, const terrain::GridMap& grid,
                    const std::vector<terrain::CellClass>& classes,
                    const MapServerOptions& options = {});

/// RGB colour of a cell in the PNG (see the file comment).
void CostColour(terrain::CellClass cell_class, float cost, uint8_t rgb[3]);

/// Writes the coloured costmap PNG. Same errors as WriteMapServer.
void WriteCostmapPng(const std::string& path, const terrain::GridMap& grid,
                     const std::vector<terrain::CellClass>& classes);

/// PNG file bytes of an RGB8 image (`rgb` = height rows of width * 3 bytes, top row first).
/// Throws std::invalid_argument for a size mismatch, std::runtime_error if libpng fails.
std::string EncodePngRgb(int width, int height, const std::vector<uint8_t>& rgb);

/// Writes one layer as an ESRI ASCII grid; `value_offset` is added to every value (the
/// elevation layer is stored in the local frame: pass origin_world.z to write world heights).
/// NaN is written as the NODATA value.
void WriteAsciiGrid(const std::string& path, const terrain::GridMap& grid, const std::string& layer,
                    double value_offset = 0.0);

/// Reads an ESRI ASCII grid into a one-layer grid named `layer` (origin_world = the file's
/// lower-left corner, NODATA -> NaN). Accepts xllcenter/yllcenter too. Throws
/// std::runtime_error naming the file and the reason (missing key, bad or missing values).
terrain::GridMap ReadAsciiGrid(const std::string& path, const std::string& layer);

/// The layers a planner needs from a costmap folder.
struct CostmapLayers {
  terrain::GridMap grid;                    ///< layers elevation (map-frame heights), cost, class
  std::vector<terrain::CellClass> classes;  ///< one per cell
};

/// Reads `dir`/layers/{elevation,cost,class}.asc as WriteTraversabilityFiles wrote them. The
/// grid's origin_world is its lower-left corner with z = 0, so local heights are the map's.
/// Throws std::runtime_error naming the file and the reason: missing or unreadable, a grid
/// that does not lie on elevation.asc's cells, a class that is not 0..3.
CostmapLayers ReadCostmapLayers(const std::string& dir);

/// Every traversability output in `dir` (created if missing): costmap.yaml + costmap.pgm,
/// costmap.png and layers/<layer>.asc for each grid layer (elevation in world heights).
/// Returns the written paths.
std::vector<std::string> WriteTraversabilityFiles(const std::string& dir,
                                                  const terrain::TraversabilityMap& map,
                                                  const MapServerOptions& options = {});

}  // namespace hylo::io
