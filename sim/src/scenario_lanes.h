#pragma once
// The lanes of a scenario's yard and the drives along them. Lanes form a grid (the yard's
// perimeter road and the roads between bays); a drive is a random walk over the grid that
// never turns back on itself. The mapping drive comes in from a start outside the fence and
// may leave the yard once through a gate for an empty spur and back; the localization drive
// keeps to lanes the mapping drive covered.

#include <Eigen/Core>
#include <functional>
#include <utility>
#include <vector>

#include "hylo/sim/random.h"
#include "hylo/sim/scenario.h"

namespace hylo::sim::scenario_site {

using V2 = Eigen::Vector2d;

/// Lane centre lines: x = xs[i] (running along y) and y = ys[j] (running along x).
struct LaneGrid {
  std::vector<double> xs, ys;
  V2 Node(int i, int j) const { return {xs[i], ys[j]}; }
  int nx() const { return static_cast<int>(xs.size()); }
  int ny() const { return static_cast<int>(ys.size()); }
};

/// Lanes 4 m inside the fence and between bays of about the recipe's size.
LaneGrid MakeLaneGrid(const SiteRecipe& recipe);

/// A lane's end at the fence, where a road leaves the yard.
struct Gate {
  int i = 0, j = 0;             ///< the lane node inside the fence
  V2 outward = V2::UnitX();     ///< unit direction out of the yard
  V2 fence_point = V2::Zero();  ///< where the road crosses the fence, m
};

struct Drives {
  std::vector<V2> route_a, route_b;  ///< waypoints, m
  V2 start = V2::Zero();             ///< the mapping drive's start, outside the fence
  V2 start_heading = V2::UnitX();    ///< unit: its first direction
  std::vector<Gate> gates;           ///< the start's gate, then the spur's if any
  /// Off-lane road segments (the approach and the spur with its turning loop), m.
  std::vector<std::pair<V2, V2>> roads;
};

/// Both drives of `recipe` on `lanes`. `driven_a_m(route_a)` says how far along route A the
/// mapping drive gets (its time may run out first): the localization drive keeps to lanes
/// completed by then.
Drives PlanDrives(const SiteRecipe& recipe, const LaneGrid& lanes, Rng* rng,
                  const std::function<double(const std::vector<V2>&)>& driven_a_m);

/// Distance from `p` to the segment [a, b], m.
double DistanceToSegment(const V2& p, const V2& a, const V2& b);

}  // namespace hylo::sim::scenario_site
