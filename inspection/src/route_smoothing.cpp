#include "hylo/inspection/route_smoothing.h"

namespace hylo::inspection {

bool SegmentPassable(const CostGrid& costs, std::size_t a, std::size_t b) {
  return WalkSupercover(costs.geometry(), a, b,
                        [&costs](std::size_t cell) { return costs.Passable(cell); });
}

std::vector<std::size_t> StraightenPath(const CostGrid& costs, const std::vector<std::size_t>& path) {
  if (path.size() <= 2) return path;
  std::vector<std::size_t> corners{path.front()};
  std::size_t from = 0;
  while (from + 1 < path.size()) {
    // Walk on while the straight line from the corner holds; the next cell of a path is
    // always in line (one legal step), so every round moves on.
    std::size_t to = from + 1;
    while (to + 1 < path.size() && SegmentPassable(costs, path[from], path[to + 1])) ++to;
    corners.push_back(path[to]);
    from = to;
  }
  return corners;
}

}  // namespace hylo::inspection
