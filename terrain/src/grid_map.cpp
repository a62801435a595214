#include "hylo/terrain/grid_map.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "hylo/common/check.h"

namespace hylo::terrain {

std::optional<Eigen::Vector2i> GridGeometry::CellOfLocal(double x_local, double y_local) const {
  if (!std::isfinite(x_local) || !std::isfinite(y_local)) return std::nullopt;
  const double col = std::floor((x_local - corner_local.x()) / resolution_m);
  const double row = std::floor((y_local - corner_local.y()) / resolution_m);
  if (col < 0 || row < 0 || col >= width || row >= height) return std::nullopt;
  return Eigen::Vector2i(static_cast<int>(col), static_cast<int>(row));
}

Eigen::Vector2d GridGeometry::CentreLocal(int col, int row) const {
  return corner_local + resolution_m * Eigen::Vector2d(col + 0.5, row + 0.5);
}

Eigen::Vector2d GridGeometry::CentreWorld(int col, int row) const {
  return origin_world.head<2>() + CentreLocal(col, row);
}

GridGeometry FitGeometry(const std::vector<const PointCloud*>& clouds_local,
                         const Eigen::Vector3d& origin_world, double resolution_m,
                         std::size_t max_cells) {
  HYLO_CHECK(resolution_m > 0.0, "resolution must be positive");
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const PointCloud* cloud : clouds_local) {
    for (const Eigen::Vector3f& p : *cloud) {
      if (!p.allFinite()) continue;
      lo = lo.cwiseMin(p.head<2>().cast<double>());
      hi = hi.cwiseMax(p.head<2>().cast<double>());
    }
  }
  GridGeometry geometry;
  geometry.origin_world = origin_world;
  geometry.resolution_m = resolution_m;
  if (!lo.allFinite()) return geometry;  // no finite point: an empty grid
  // Corners on multiples of the resolution (grids of equal resolution line up); the extent
  // is counted from the floored corner so the highest point still falls inside.
  geometry.corner_local = (lo / resolution_m).array().floor().matrix() * resolution_m;
  const Eigen::Vector2d extent = (hi - geometry.corner_local) / resolution_m;
  const double num_cells = (std::floor(extent.x()) + 1) * (std::floor(extent.y()) + 1);
  if (num_cells > static_cast<double>(max_cells)) {
    std::ostringstream os;
    os << "the points span " << (hi - lo).x() << " m x " << (hi - lo).y() << " m: a grid of "
       << num_cells << " cells at " << resolution_m << " m exceeds the limit of " << max_cells
       << " (remove far outliers or use a coarser resolution)";
    throw std::runtime_error(os.str());
  }
  geometry.width = static_cast<int>(std::floor(extent.x())) + 1;
  geometry.height = static_cast<int>(std::floor(extent.y())) + 1;
  return geometry;
}

CellPoints BinPoints(const GridGeometry& geometry, const PointCloud& cloud_local) {
  CellPoints bins;
  bins.offsets.assign(geometry.NumCells() + 1, 0);
  std::vector<std::size_t> cell_of_point(cloud_local.size(), geometry.NumCells());
  for (std::size_t i = 0; i < cloud_local.size(); ++i) {
    const Eigen::Vector3f& p = cloud_local[i];
    const auto cell = p.allFinite() ? geometry.CellOfLocal(p.x(), p.y()) : std::nullopt;
    if (!cell) {
      ++bins.num_skipped;
      continue;
    }
    cell_of_point[i] = geometry.Index(cell->x(), cell->y());
    ++bins.offsets[cell_of_point[i] + 1];
  }
  for (std::size_t c = 0; c < geometry.NumCells(); ++c) bins.offsets[c + 1] += bins.offsets[c];
  bins.point_indices.resize(bins.offsets.back());
  std::vector<std::size_t> next(bins.offsets.begin(), bins.offsets.end() - 1);
  for (std::size_t i = 0; i < cloud_local.size(); ++i) {
    if (cell_of_point[i] == geometry.NumCells()) continue;
    bins.point_indices[next[cell_of_point[i]]++] = i;
  }
  return bins;
}

std::vector<float>& GridMap::AddLayer(const std::string& name, float value) {
  std::vector<float>& layer = layers_[name];
  layer.assign(geometry_.NumCells(), value);
  return layer;
}

const std::vector<float>& GridMap::Layer(const std::string& name) const {
  const auto it = layers_.find(name);
  HYLO_CHECK(it != layers_.end(), "no such grid layer");
  return it->second;
}

std::vector<float>& GridMap::MutableLayer(const std::string& name) {
  const auto it = layers_.find(name);
  HYLO_CHECK(it != layers_.end(), "no such grid layer");
  return it->second;
}

std::vector<std::string> GridMap::LayerNames() const {
  std::vector<std::string> names;
  for (const auto& [name, layer] : layers_) names.push_back(name);
  return names;
}

float GridMap::At(const std::string& name, int col, int row) const {
  if (!geometry_.Contains(col, row)) return std::numeric_limits<float>::quiet_NaN();
  return Layer(name)[geometry_.Index(col, row)];
}

}  // namespace hylo::terrain
