#include "hylo/terrain/grid_map_elevation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "hylo/common/check.h"

namespace hylo::terrain {
namespace {

constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();

/// One 4-connected region of empty cells.
struct Region {
  std::vector<std::size_t> cells;
  Eigen::Vector2i min_cell{std::numeric_limits<int>::max(), std::numeric_limits<int>::max()};
  Eigen::Vector2i max_cell{-1, -1};
  bool touches_border = false;
};

Region FloodEmptyRegion(const GridGeometry& g, const std::vector<float>& elevation,
                        std::size_t seed, std::vector<char>* visited) {
  Region region;
  std::vector<std::size_t> stack = {seed};
  (*visited)[seed] = 1;
  while (!stack.empty()) {
    const std::size_t cell = stack.back();
    stack.pop_back();
    region.cells.push_back(cell);
    const Eigen::Vector2i c(g.Col(cell), g.Row(cell));
    region.min_cell = region.min_cell.cwiseMin(c);
    region.max_cell = region.max_cell.cwiseMax(c);
    static const int kDc[4] = {1, -1, 0, 0}, kDr[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int col = c.x() + kDc[k], row = c.y() + kDr[k];
      if (!g.Contains(col, row)) {
        region.touches_border = true;
        continue;
      }
      const std::size_t next = g.Index(col, row);
      if ((*visited)[next] || !std::isnan(elevation[next])) continue;
      (*visited)[next] = 1;
      stack.push_back(next);
    }
  }
  return region;
}

/// Known cells 8-adjacent to the region: the values the hole is interpolated from.
std::vector<std::size_t> RegionBorder(const GridGeometry& g, const std::vector<float>& elevation,
                                      const Region& region) {
  std::vector<std::size_t> border;
  for (const std::size_t cell : region.cells) {
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const int col = g.Col(cell) + dc, row = g.Row(cell) + dr;
        if (g.Contains(col, row) && !std::isnan(elevation[g.Index(col, row)])) {
          border.push_back(g.Index(col, row));
        }
      }
    }
  }
  std::sort(border.begin(), border.end());
  border.erase(std::unique(border.begin(), border.end()), border.end());
  return border;
}

void InterpolateRegion(const GridGeometry& g, const Region& region,
                       const std::vector<std::size_t>& border, std::vector<float>* elevation,
                       std::vector<float>* filled) {
  for (const std::size_t cell : region.cells) {
    double weight_sum = 0.0, value_sum = 0.0;
    for (const std::size_t b : border) {
      const double dc = g.Col(b) - g.Col(cell), dr = g.Row(b) - g.Row(cell);
      const double w = 1.0 / (dc * dc + dr * dr);  // inverse distance squared, d >= 1 cell
      weight_sum += w;
      value_sum += w * (*elevation)[b];
    }
    (*elevation)[cell] = static_cast<float>(value_sum / weight_sum);
    (*filled)[cell] = 1.f;
  }
}

}  // namespace

bool ElevationOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (min_points_per_cell < 1) {
    os << "min_points_per_cell = " << min_points_per_cell << " must be >= 1";
  } else if (!(max_hole_size_m >= 0.0) || !std::isfinite(max_hole_size_m)) {
    os << "max_hole_size_m = " << max_hole_size_m << " must be finite and >= 0";
  }
  if (why) *why = os.str();
  return os.str().empty();
}

ElevationSummary FillHoles(const GridGeometry& geometry, int max_hole_cells,
                           std::vector<float>* elevation, std::vector<float>* filled) {
  HYLO_CHECK(elevation->size() == geometry.NumCells() && filled->size() == elevation->size(),
             "layers do not match the grid");
  ElevationSummary summary;
  std::vector<char> visited(elevation->size(), 0);
  const std::vector<float> measured = *elevation;  // holes interpolate measured cells only
  for (std::size_t seed = 0; seed < measured.size(); ++seed) {
    if (visited[seed] || !std::isnan(measured[seed])) continue;
    const Region region = FloodEmptyRegion(geometry, measured, seed, &visited);
    if (region.touches_border) continue;  // open to the outside: unseen land, not a hole
    const Eigen::Vector2i size = region.max_cell - region.min_cell + Eigen::Vector2i::Ones();
    if (size.maxCoeff() > max_hole_cells) {
      ++summary.holes_too_large;
      continue;
    }
    InterpolateRegion(geometry, region, RegionBorder(geometry, measured, region), elevation,
                      filled);
    ++summary.holes_filled;
    summary.filled_cells += region.cells.size();
  }
  return summary;
}

ElevationSummary ComputeElevation(const PointCloud& ground_local, const CellPoints& bins,
                                  const ElevationOptions& options, GridMap* grid) {
  const GridGeometry& g = grid->geometry();
  HYLO_CHECK(bins.offsets.size() == g.NumCells() + 1, "bins come from another grid");
  std::vector<float>& elevation = grid->AddLayer(layers::kElevation, kNoData);
  std::vector<float>& count = grid->AddLayer(layers::kPointCount, 0.f);
  std::vector<float>& filled = grid->AddLayer(layers::kFilled, 0.f);
  std::size_t measured = 0;
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    const std::size_t n = bins.Count(cell);
    count[cell] = static_cast<float>(n);
    if (n < static_cast<std::size_t>(options.min_points_per_cell)) continue;
    double z_sum = 0.0;
    for (std::size_t k = bins.offsets[cell]; k < bins.offsets[cell + 1]; ++k) {
      z_sum += ground_local[bins.point_indices[k]].z();
    }
    elevation[cell] = static_cast<float>(z_sum / n);
    ++measured;
  }
  // A hole fits when its bounding box is <= max_hole_size_m: floor keeps the bound strict.
  const int max_hole_cells =
      static_cast<int>(std::floor(options.max_hole_size_m / g.resolution_m + 1e-9));
  ElevationSummary summary;
  if (max_hole_cells > 0) summary = FillHoles(g, max_hole_cells, &elevation, &filled);
  summary.measured_cells = measured;
  return summary;
}

}  // namespace hylo::terrain
