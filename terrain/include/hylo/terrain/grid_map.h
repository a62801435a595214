#pragma once
// A 2.5-D grid map: a regular grid over the xy plane with named float layers (elevation,
// slope, ...). Cells are computed in a local frame near zero (float-safe); the grid keeps
// the world position of that frame in double so UTM-sized sites are written back exactly.
//
// Indexing: column = x, row = y; cell (0,0) is the lower-left (south-west) cell, as in the
// ROS map_server convention. Storage is row-major: index = row * width + col. A NaN value
// means "no data" in every layer.

#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hylo/common/point_types.h"

namespace hylo::terrain {

/// Where the grid lies. Local coordinates are world minus `origin_world`.
struct GridGeometry {
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();  ///< world position of local 0, m
  Eigen::Vector2d corner_local = Eigen::Vector2d::Zero();  ///< local xy of cell (0,0)'s outer
                                                           ///< lower-left corner, m
  double resolution_m = 0.1;                               ///< cell edge, m
  int width = 0;                                           ///< cells along x
  int height = 0;                                          ///< cells along y

  std::size_t NumCells() const { return static_cast<std::size_t>(width) * height; }
  bool Contains(int col, int row) const {
    return col >= 0 && row >= 0 && col < width && row < height;
  }
  std::size_t Index(int col, int row) const { return static_cast<std::size_t>(row) * width + col; }
  int Col(std::size_t index) const { return static_cast<int>(index % width); }
  int Row(std::size_t index) const { return static_cast<int>(index / width); }
  /// Cell holding a local xy position; nullopt outside the grid or for non-finite input.
  std::optional<Eigen::Vector2i> CellOfLocal(double x_local, double y_local) const;
  /// Local xy of a cell centre.
  Eigen::Vector2d CentreLocal(int col, int row) const;
  /// World xy of a cell centre (double: exact for UTM coordinates).
  Eigen::Vector2d CentreWorld(int col, int row) const;
  /// World xy of the grid's lower-left corner: the map_server `origin` and the grid header.
  Eigen::Vector2d CornerWorld() const { return origin_world.head<2>() + corner_local; }
};

/// The smallest grid of `resolution_m` cells covering every finite point of `clouds_local`
/// (local frame), with corners on multiples of the resolution so that grids of the same
/// resolution built from different clouds line up. Width/height 0 when no point is finite.
/// Throws std::runtime_error when the grid would exceed `max_cells` (a far outlier point or
/// a resolution too fine for the site), naming the size it would have.
GridGeometry FitGeometry(const std::vector<const PointCloud*>& clouds_local,
                         const Eigen::Vector3d& origin_world, double resolution_m,
                         std::size_t max_cells);

/// Points grouped by cell (compressed rows): the points of cell i are
/// `point_indices[offsets[i] .. offsets[i+1])`. Points outside the grid or non-finite are
/// left out and counted.
struct CellPoints {
  std::vector<std::size_t> offsets;        ///< NumCells() + 1 entries
  std::vector<std::size_t> point_indices;  ///< into the binned cloud
  std::size_t num_skipped = 0;             ///< non-finite or outside the grid

  std::size_t Count(std::size_t cell) const { return offsets[cell + 1] - offsets[cell]; }
};
CellPoints BinPoints(const GridGeometry& geometry, const PointCloud& cloud_local);

/// Named float layers over one geometry.
class GridMap {
 public:
  GridMap() = default;
  explicit GridMap(GridGeometry geometry) : geometry_(std::move(geometry)) {}

  const GridGeometry& geometry() const { return geometry_; }

  /// Adds (or resets) a layer filled with `value` (NaN = no data) and returns it.
  std::vector<float>& AddLayer(const std::string& name, float value);
  bool HasLayer(const std::string& name) const { return layers_.count(name) > 0; }
  /// The layer; HYLO_CHECK fails for a name that was never added (a programmer error).
  const std::vector<float>& Layer(const std::string& name) const;
  std::vector<float>& MutableLayer(const std::string& name);
  std::vector<std::string> LayerNames() const;

  /// Value at a cell, NaN outside the grid.
  float At(const std::string& name, int col, int row) const;

 private:
  GridGeometry geometry_;
  std::map<std::string, std::vector<float>> layers_;
};

/// Layer names used by the traversability pipeline (and the exported file names).
namespace layers {
inline constexpr const char* kElevation = "elevation";     ///< m, local frame z
inline constexpr const char* kPointCount = "point_count";  ///< ground points per cell
inline constexpr const char* kFilled = "filled";           ///< 1 where hole filling wrote
inline constexpr const char* kNormalX = "normal_x";        ///< unit normal, z up
inline constexpr const char* kNormalY = "normal_y";
inline constexpr const char* kNormalZ = "normal_z";
inline constexpr const char* kSlope = "slope";          ///< deg from horizontal
inline constexpr const char* kRoughness = "roughness";  ///< m, RMS distance to plane
inline constexpr const char* kStep = "step";            ///< m, max height difference
inline constexpr const char* kCost = "cost";            ///< 0..1, 1 = lethal
inline constexpr const char* kClass = "class";          ///< CellClass as a number
}  // namespace layers

}  // namespace hylo::terrain
