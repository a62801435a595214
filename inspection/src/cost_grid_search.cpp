#include "hylo/inspection/cost_grid_search.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <utility>

#include "hylo/common/check.h"
#include "hylo/common/option_checks.h"

namespace hylo::inspection {
namespace {

using terrain::CellClass;
using QueueEntry = std::pair<double, std::size_t>;  // (key, cell)
using MinQueue = std::priority_queue<QueueEntry, std::vector<QueueEntry>, std::greater<>>;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kNone = static_cast<std::size_t>(-1);

bool Traversable(CellClass c) { return c == CellClass::kFree || c == CellClass::kCost; }

}  // namespace

bool SearchOptions::IsValid(std::string* why) const {
  return CheckNonNegative("robot_radius_m", robot_radius_m, why) &&
         CheckNonNegative("cost_weight", cost_weight, why);
}

std::vector<uint8_t> PassableCells(const terrain::GridGeometry& geometry,
                                   const std::vector<CellClass>& classes, double robot_radius_m) {
  HYLO_CHECK(classes.size() == geometry.NumCells(), "one class per cell");
  std::vector<uint8_t> passable(classes.size());
  for (std::size_t i = 0; i < classes.size(); ++i) passable[i] = Traversable(classes[i]);
  const int r = static_cast<int>(std::floor(robot_radius_m / geometry.resolution_m + 1e-9));
  const double r2 = std::pow(robot_radius_m / geometry.resolution_m, 2) + 1e-9;
  std::vector<std::pair<int, int>> disc;
  for (int dr = -r; dr <= r; ++dr) {
    for (int dc = -r; dc <= r; ++dc) {
      if ((dr != 0 || dc != 0) && dr * dr + dc * dc <= r2) disc.emplace_back(dc, dr);
    }
  }
  for (std::size_t i = 0; i < classes.size(); ++i) {
    if (classes[i] != CellClass::kLethal) continue;
    const int col = geometry.Col(i), row = geometry.Row(i);
    for (const auto& [dc, dr] : disc) {
      if (geometry.Contains(col + dc, row + dr)) passable[geometry.Index(col + dc, row + dr)] = 0;
    }
  }
  return passable;
}

CostGrid::CostGrid(const terrain::GridGeometry& geometry, std::vector<uint8_t> passable,
                   const std::vector<float>& cost, double cost_weight)
    : geometry_(geometry), passable_(std::move(passable)), factor_(geometry.NumCells()) {
  HYLO_CHECK(passable_.size() == geometry.NumCells() && cost.size() == geometry.NumCells(),
             "one value per cell");
  for (std::size_t i = 0; i < cost.size(); ++i) {
    const float c = std::isnan(cost[i]) ? 1.f : std::clamp(cost[i], 0.f, 1.f);
    factor_[i] = static_cast<float>(1.0 + cost_weight * c);
  }
}

std::vector<double> CostGrid::Distances(std::size_t source,
                                        const std::vector<std::size_t>& wanted) const {
  std::vector<double> dist(geometry_.NumCells(), kInf);
  if (source >= dist.size() || !passable_[source]) return dist;
  std::vector<uint8_t> is_wanted(wanted.empty() ? 0 : dist.size(), 0);
  std::size_t pending = 0;
  for (const std::size_t w : wanted) {
    if (w < dist.size() && passable_[w] && !is_wanted[w]) {
      is_wanted[w] = 1;
      ++pending;
    }
  }
  MinQueue queue;
  dist[source] = 0.0;
  queue.push({0.0, source});
  while (!queue.empty()) {
    const auto [d, cell] = queue.top();
    queue.pop();
    if (d > dist[cell]) continue;  // a stale entry
    if (!wanted.empty() && is_wanted[cell] && --pending == 0) break;
    ForEachStep(cell, [&](std::size_t next, double step, double) {
      if (d + step < dist[next]) {
        dist[next] = d + step;
        queue.push({dist[next], next});
      }
    });
  }
  return dist;
}

GridPath CostGrid::ShortestPath(std::size_t from, std::size_t to) const {
  GridPath path;
  const std::size_t n = geometry_.NumCells();
  if (from >= n || to >= n || !passable_[from] || !passable_[to]) return path;
  const int to_col = geometry_.Col(to), to_row = geometry_.Row(to);
  const auto heuristic = [&](std::size_t cell) {
    const int dx = std::abs(geometry_.Col(cell) - to_col), dy = std::abs(geometry_.Row(cell) - to_row);
    return geometry_.resolution_m * (std::max(dx, dy) + (M_SQRT2 - 1.0) * std::min(dx, dy));
  };
  std::vector<double> g(n, kInf);
  std::vector<std::size_t> parent(n, kNone);
  std::vector<uint8_t> closed(n, 0);
  MinQueue open;
  g[from] = 0.0;
  open.push({heuristic(from), from});
  while (!open.empty()) {
    const std::size_t cell = open.top().second;
    open.pop();
    if (closed[cell]) continue;
    closed[cell] = 1;
    if (cell == to) break;
    ForEachStep(cell, [&](std::size_t next, double step, double) {
      if (!closed[next] && g[cell] + step < g[next]) {
        g[next] = g[cell] + step;
        parent[next] = cell;
        open.push({g[next] + heuristic(next), next});
      }
    });
  }
  if (!closed[to]) return path;
  for (std::size_t c = to; c != kNone; c = parent[c]) path.cells.push_back(c);
  std::reverse(path.cells.begin(), path.cells.end());
  path.cost = g[to];
  for (std::size_t i = 1; i < path.cells.size(); ++i) {
    const bool diagonal = geometry_.Col(path.cells[i]) != geometry_.Col(path.cells[i - 1]) &&
                          geometry_.Row(path.cells[i]) != geometry_.Row(path.cells[i - 1]);
    path.length_m += geometry_.resolution_m * (diagonal ? M_SQRT2 : 1.0);
  }
  return path;
}

}  // namespace hylo::inspection
