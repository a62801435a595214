#include "hylo/mapping/cloth_filter_surface.h"

#include <cmath>
#include <limits>

#include "hylo/common/check.h"

namespace hylo::mapping::cloth {
namespace {
constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
constexpr int kNeighbourCol[4] = {1, -1, 0, 0};
constexpr int kNeighbourRow[4] = {0, 0, 1, -1};
}  // namespace

InvertedSurface RasterizeInvertedSurface(const ClothGrid& grid,
                                         const registration::PointCloud& points_inverted) {
  InvertedSurface surface;
  surface.height_m.assign(grid.Size(), kUnknown);
  std::vector<double> best_distance2(grid.Size(), std::numeric_limits<double>::infinity());
  for (const Eigen::Vector3f& p : points_inverted) {
    const Eigen::Vector2d cell = (p.head<2>().cast<double>() - grid.origin_xy) / grid.resolution_m;
    const int col = static_cast<int>(std::lround(cell.x()));
    const int row = static_cast<int>(std::lround(cell.y()));
    if (!grid.Contains(col, row)) continue;
    const double distance2 = (cell - Eigen::Vector2d(col, row)).squaredNorm();
    const std::size_t index = grid.Index(col, row);
    if (distance2 < best_distance2[index]) {
      best_distance2[index] = distance2;
      surface.height_m[index] = p.z();
    }
  }
  surface.num_filled_holes = FillHoles(grid, &surface.height_m);
  return surface;
}

std::size_t FillHoles(const ClothGrid& grid, std::vector<double>* height_m) {
  HYLO_CHECK(height_m != nullptr && height_m->size() == grid.Size(), "one height per particle");
  std::vector<double>& height = *height_m;
  std::vector<std::size_t> frontier;
  for (std::size_t i = 0; i < height.size(); ++i) {
    if (!std::isnan(height[i])) frontier.push_back(i);
  }
  HYLO_CHECK(!frontier.empty(), "no point inside the cloth grid");
  std::size_t filled = 0;
  std::vector<uint8_t> queued(height.size(), 0);
  while (!frontier.empty()) {
    // The next ring: unknown particles touching the current frontier.
    std::vector<std::size_t> ring;
    for (const std::size_t i : frontier) {
      const int col = static_cast<int>(i % grid.cols);
      const int row = static_cast<int>(i / grid.cols);
      for (int k = 0; k < 4; ++k) {
        const int c = col + kNeighbourCol[k];
        const int r = row + kNeighbourRow[k];
        if (!grid.Contains(c, r)) continue;
        const std::size_t j = grid.Index(c, r);
        if (std::isnan(height[j]) && !queued[j]) {
          queued[j] = 1;
          ring.push_back(j);
        }
      }
    }
    // Mean of known neighbours, computed for the whole ring before writing any, so the
    // result does not depend on the visiting order.
    std::vector<double> values(ring.size(), 0.0);
    for (std::size_t n = 0; n < ring.size(); ++n) {
      const int col = static_cast<int>(ring[n] % grid.cols);
      const int row = static_cast<int>(ring[n] / grid.cols);
      double sum = 0.0;
      int count = 0;
      for (int k = 0; k < 4; ++k) {
        const int c = col + kNeighbourCol[k];
        const int r = row + kNeighbourRow[k];
        if (!grid.Contains(c, r) || std::isnan(height[grid.Index(c, r)])) continue;
        sum += height[grid.Index(c, r)];
        ++count;
      }
      values[n] = sum / count;  // count >= 1: the particle touches the frontier
    }
    for (std::size_t n = 0; n < ring.size(); ++n) height[ring[n]] = values[n];
    filled += ring.size();
    frontier.swap(ring);
  }
  return filled;
}

}  // namespace hylo::mapping::cloth
