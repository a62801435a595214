#include "hylo/terrain/cloth_filter_slope.h"

#include <cmath>
#include <deque>

#include "hylo/common/check.h"

namespace hylo::terrain::cloth {
namespace {

constexpr int kNeighbourCol[4] = {1, -1, 0, 0};
constexpr int kNeighbourRow[4] = {0, 0, 1, -1};

// Marks the movable particles that belong to 4-connected movable regions of more than
// `min_region_particles` particles: only those are candidates for the slope correction.
std::vector<uint8_t> LargeMovableRegions(const Cloth& cloth, std::size_t min_region_particles) {
  const ClothGrid& grid = cloth.grid();
  std::vector<uint8_t> visited(grid.Size(), 0), large(grid.Size(), 0);
  for (std::size_t seed = 0; seed < grid.Size(); ++seed) {
    if (visited[seed] || !cloth.IsMovable(seed)) continue;
    std::vector<std::size_t> region = {seed};
    visited[seed] = 1;
    for (std::size_t k = 0; k < region.size(); ++k) {
      const int col = static_cast<int>(region[k] % grid.cols);
      const int row = static_cast<int>(region[k] / grid.cols);
      for (int n = 0; n < 4; ++n) {
        const int c = col + kNeighbourCol[n], r = row + kNeighbourRow[n];
        if (!grid.Contains(c, r)) continue;
        const std::size_t j = grid.Index(c, r);
        if (visited[j] || !cloth.IsMovable(j)) continue;
        visited[j] = 1;
        region.push_back(j);
      }
    }
    if (region.size() <= min_region_particles) continue;
    for (const std::size_t i : region) large[i] = 1;
  }
  return large;
}

}  // namespace

std::size_t SmoothSteepSlopes(const std::vector<double>& surface_height_m,
                              double height_threshold_m, double max_cloth_gap_m,
                              std::size_t min_region_particles, Cloth* cloth) {
  HYLO_CHECK(cloth != nullptr && surface_height_m.size() == cloth->grid().Size(),
             "one surface height per particle");
  const ClothGrid& grid = cloth->grid();
  const std::vector<uint8_t> candidate = LargeMovableRegions(*cloth, min_region_particles);
  // Breadth-first from every pinned particle, so corrections grow outwards from the terrain
  // the cloth already touches: a particle is pinned when its surface height continues its
  // pinned neighbour's surface height (a slope), not when it jumps (a wall, an object).
  std::deque<std::size_t> queue;
  for (std::size_t i = 0; i < grid.Size(); ++i) {
    if (!cloth->IsMovable(i)) queue.push_back(i);
  }
  std::size_t pinned = 0;
  while (!queue.empty()) {
    const std::size_t from = queue.front();
    queue.pop_front();
    const int col = static_cast<int>(from % grid.cols);
    const int row = static_cast<int>(from / grid.cols);
    for (int k = 0; k < 4; ++k) {
      const int c = col + kNeighbourCol[k];
      const int r = row + kNeighbourRow[k];
      if (!grid.Contains(c, r)) continue;
      const std::size_t to = grid.Index(c, r);
      if (!candidate[to] || !cloth->IsMovable(to)) continue;
      if (std::abs(surface_height_m[to] - surface_height_m[from]) >= height_threshold_m) continue;
      // Inverted frame: the cloth rests on or above the surface; a large gap is an object.
      if (cloth->heights()[to] - surface_height_m[to] >= max_cloth_gap_m) continue;
      cloth->Pin(to, surface_height_m[to]);
      queue.push_back(to);
      ++pinned;
    }
  }
  return pinned;
}

}  // namespace hylo::terrain::cloth
