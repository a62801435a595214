#pragma once
// Shortest paths on the traversability costmap: Dijkstra from one cell (reachability from the
// start, travel costs between viewpoints) and A* between two cells (the route's legs).
//
// The robot's centre moves from cell centre to cell centre, 8-connected. A diagonal step is
// allowed only when both cells it passes between (the two orthogonal neighbours) are passable
// too, so a route never cuts the corner of a lethal or unknown cell: the straight segment of
// every step stays inside passable cells. A step from a to b costs its length times
// 1 + cost_weight * (cost[a] + cost[b]) / 2 (cost in 0..1 from the costmap), so the costs are
// symmetric and never below the length: the octile distance is an admissible, consistent A*
// heuristic and A* finds a path as cheap as Dijkstra's.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "hylo/terrain/grid_map.h"
#include "hylo/terrain/traversability_cost.h"

namespace hylo::inspection {

struct SearchOptions {
  double robot_radius_m = 0.3;  ///< the robot's centre keeps this far from lethal cells
                                ///< (their centres), m
  double cost_weight = 2.0;     ///< extra cost of a step per unit of cell cost (a cell just
                                ///< below lethal counts 1 + cost_weight times its length), >= 0

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

/// Where the robot's centre may be: free and cost cells farther than `robot_radius_m` from
/// every lethal cell (centre to centre). Unknown and lethal cells are never passable; unknown
/// cells are not grown (the map's holes would close lanes), lethal ones are.
std::vector<uint8_t> PassableCells(const terrain::GridGeometry& geometry,
                                   const std::vector<terrain::CellClass>& classes,
                                   double robot_radius_m);

/// A path from one cell to another, both included.
struct GridPath {
  std::vector<std::size_t> cells;  ///< empty when there is none
  double cost = std::numeric_limits<double>::infinity();  ///< weighted, m
  double length_m = 0.0;                                  ///< geometric, m
  bool found() const { return !cells.empty(); }
};

class CostGrid {
 public:
  /// `passable` and `cost` (0..1, NaN read as 1) hold one value per cell of `geometry`.
  CostGrid(const terrain::GridGeometry& geometry, std::vector<uint8_t> passable,
           const std::vector<float>& cost, double cost_weight);

  /// Cost from `source` to every cell (Dijkstra), +inf where unreachable or impassable. With
  /// `wanted` not empty, stops once all of those cells are settled (others may stay +inf or
  /// hold an upper bound).
  std::vector<double> Distances(std::size_t source, const std::vector<std::size_t>& wanted = {}) const;

  /// The cheapest path (A*, octile heuristic); not found when either end is impassable or
  /// they are not connected.
  GridPath ShortestPath(std::size_t from, std::size_t to) const;

  bool Passable(std::size_t cell) const { return passable_[cell] != 0; }
  const terrain::GridGeometry& geometry() const { return geometry_; }

  /// Calls visit(neighbour, step_cost, step_length_m) for every allowed step from `cell`.
  template <class Visit>
  void ForEachStep(std::size_t cell, Visit&& visit) const;

 private:
  terrain::GridGeometry geometry_;
  std::vector<uint8_t> passable_;
  std::vector<float> factor_;  ///< 1 + cost_weight * cost per cell
};

template <class Visit>
void CostGrid::ForEachStep(std::size_t cell, Visit&& visit) const {
  static constexpr int kDc[8] = {1, -1, 0, 0, 1, 1, -1, -1};
  static constexpr int kDr[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  const int width = geometry_.width;
  const int row = static_cast<int>(cell / width), col = static_cast<int>(cell) - row * width;
  const bool inside = col > 0 && row > 0 && col + 1 < width && row + 1 < geometry_.height;
  const double res = geometry_.resolution_m;
  for (int k = 0; k < 8; ++k) {
    if (!inside && !geometry_.Contains(col + kDc[k], row + kDr[k])) continue;
    const std::size_t next = cell + kDc[k] + static_cast<std::ptrdiff_t>(kDr[k]) * width;
    if (!passable_[next]) continue;
    const bool diagonal = k >= 4;
    if (diagonal && !(passable_[cell + kDc[k]] &&
                      passable_[cell + static_cast<std::ptrdiff_t>(kDr[k]) * width]))
      continue;  // would cut the corner of an impassable cell
    const double length = diagonal ? res * M_SQRT2 : res;
    visit(next, length * 0.5 * (factor_[cell] + factor_[next]), length);
  }
}

}  // namespace hylo::inspection
