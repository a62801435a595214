// Lane grid and drives: random walks that never turn back, a shortest way to a gate that
// never turns back either (breadth-first over node and arrival direction).
#include "scenario_lanes.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <iterator>
#include <map>
#include <set>

#include "hylo/common/check.h"

namespace hylo::sim::scenario_site {
namespace {

constexpr double kLaneInsetM = 4.0;  // perimeter lanes inside the fence, m
constexpr double kApproachM = 20.0;  // the start lies this far outside the fence, m
constexpr double kSpurLoopM = 8.0;   // the spur's turning loop reaches this far beyond it, m

std::vector<double> Lines(double extent_m, double bay_m) {
  const double inner = extent_m - 2.0 * kLaneInsetM;
  const int bays = std::max(1, static_cast<int>(std::lround(inner / bay_m)));
  std::vector<double> lines;
  for (int k = 0; k <= bays; ++k) lines.push_back(kLaneInsetM + inner * k / bays);
  return lines;
}

using Edges = std::set<std::pair<int, int>>;

class Walker {
 public:
  /// `allowed`: the lanes the walk may take (null: all).
  Walker(const LaneGrid& lanes, Rng* rng, const Edges* allowed = nullptr)
      : lanes_(lanes), rng_(rng), allowed_(allowed) {}

  int Index(int i, int j) const { return i * lanes_.ny() + j; }
  V2 Position(int node) const { return lanes_.Node(node / lanes_.ny(), node % lanes_.ny()); }

  std::vector<int> Neighbours(int node) const {
    const int i = node / lanes_.ny(), j = node % lanes_.ny();
    std::vector<int> out;
    if (i > 0) out.push_back(Index(i - 1, j));
    if (i + 1 < lanes_.nx()) out.push_back(Index(i + 1, j));
    if (j > 0) out.push_back(Index(i, j - 1));
    if (j + 1 < lanes_.ny()) out.push_back(Index(i, j + 1));
    if (allowed_ != nullptr) {
      out.erase(std::remove_if(out.begin(), out.end(),
                               [&](int n) { return !allowed_->count(Edge(node, n)); }),
                out.end());
    }
    return out;
  }

  // One step from `node`, never back to `previous`; unvisited lanes are preferred. -1 when
  // the allowed lanes end there.
  int Step(int node, int previous) {
    std::vector<int> options, fresh;
    for (const int n : Neighbours(node)) {
      if (n == previous) continue;
      options.push_back(n);
      if (!reached_at_m_.count(Edge(node, n))) fresh.push_back(n);
    }
    if (options.empty()) {
      HYLO_CHECK(allowed_ != nullptr, "a full lane grid has no dead ends");
      return -1;
    }
    const std::vector<int>& pool = !fresh.empty() && rng_->Uniform() < 0.85 ? fresh : options;
    return pool[std::min<std::size_t>(pool.size() - 1,
                                      static_cast<std::size_t>(rng_->Uniform() * pool.size()))];
  }

  // Drives from `*node` to its neighbour `next`.
  void Drive(int next, int* node, int* previous, std::vector<V2>* route) {
    odometer_m_ += (Position(next) - Position(*node)).norm();
    reached_at_m_.emplace(Edge(*node, next), odometer_m_);  // keeps the first time
    route->push_back(Position(next));
    *previous = *node;
    *node = next;
  }

  // Walks from `*node` (arrived from `*previous`, -1 = anywhere) until `length_m` more metres
  // have been driven, appending the nodes.
  void Walk(double length_m, int* node, int* previous, std::vector<V2>* route) {
    const double end_m = odometer_m_ + length_m;
    while (odometer_m_ < end_m) {
      const int next = Step(*node, *previous);
      if (next < 0) return;
      Drive(next, node, previous, route);
    }
  }

  // The shortest way from `*node` to `target` that never turns back, appended.
  void GoTo(int target, int* node, int* previous, std::vector<V2>* route) {
    if (*node == target) return;
    using State = std::pair<int, int>;  // node, previous
    std::deque<State> queue{{*node, *previous}};
    std::set<State> seen{{*node, *previous}};
    std::vector<std::pair<State, State>> parent;  // state, where it came from
    State reached{-1, -1};
    while (!queue.empty() && reached.first < 0) {
      const State s = queue.front();
      queue.pop_front();
      for (const int n : Neighbours(s.first)) {
        const State next{n, s.first};
        if (n == s.second || !seen.insert(next).second) continue;
        parent.push_back({next, s});
        if (n == target) {
          reached = next;
          break;
        }
        queue.push_back(next);
      }
    }
    HYLO_CHECK(reached.first >= 0, "every lane node is reachable without turning back");
    std::vector<int> path;
    for (State s = reached; s != State{*node, *previous};) {
      path.push_back(s.first);
      s = std::find_if(parent.begin(), parent.end(), [&](const auto& p) {
            return p.first == s;
          })->second;
    }
    std::reverse(path.begin(), path.end());
    for (const int n : path) Drive(n, node, previous, route);
  }

  // Off the lanes (the spur): only the odometer runs.
  void DriveOff(const std::vector<V2>& from_to, std::vector<V2>* route) {
    for (std::size_t k = 1; k < from_to.size(); ++k) {
      odometer_m_ += (from_to[k] - from_to[k - 1]).norm();
      route->push_back(from_to[k]);
    }
  }

  // The lanes this walk completed within its first `distance_m` metres.
  Edges ReachedWithin(double distance_m) const {
    Edges edges;
    for (const auto& [edge, at_m] : reached_at_m_) {
      if (at_m <= distance_m) edges.insert(edge);
    }
    return edges;
  }

  // A node at an end of one of `edges` (not empty).
  int NodeOf(const Edges& edges) {
    const std::size_t k =
        std::min(edges.size() - 1, static_cast<std::size_t>(rng_->Uniform() * edges.size()));
    return std::next(edges.begin(), static_cast<std::ptrdiff_t>(k))->first;
  }

 private:
  static std::pair<int, int> Edge(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

  const LaneGrid& lanes_;
  Rng* rng_;
  const Edges* allowed_;
  std::map<std::pair<int, int>, double> reached_at_m_;  // lane -> odometer when first driven
  double odometer_m_ = 0.0;
};

Gate DrawGate(const LaneGrid& lanes, int side, Rng* rng) {
  Gate gate;
  const bool vertical_side = side < 2;  // west / east: the road runs along x
  const int count = vertical_side ? lanes.ny() : lanes.nx();
  const int k = std::min(count - 1, static_cast<int>(rng->Uniform() * count));
  gate.i = vertical_side ? (side == 0 ? 0 : lanes.nx() - 1) : k;
  gate.j = vertical_side ? k : (side == 2 ? 0 : lanes.ny() - 1);
  const V2 directions[4] = {V2(-1, 0), V2(1, 0), V2(0, -1), V2(0, 1)};
  gate.outward = directions[side];
  gate.fence_point = lanes.Node(gate.i, gate.j) + kLaneInsetM * gate.outward;
  return gate;
}

// Drops waypoints where the route goes straight on.
std::vector<V2> Simplified(const std::vector<V2>& route) {
  std::vector<V2> out{route.front()};
  for (std::size_t k = 1; k + 1 < route.size(); ++k) {
    const V2 in = route[k] - out.back(), next = route[k + 1] - route[k];
    const double cross = in.x() * next.y() - in.y() * next.x();
    if (std::abs(cross) < 1e-9 * in.norm() * next.norm() && in.dot(next) > 0.0) continue;
    out.push_back(route[k]);
  }
  out.push_back(route.back());
  return out;
}

}  // namespace

double DistanceToSegment(const V2& p, const V2& a, const V2& b) {
  const V2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

LaneGrid MakeLaneGrid(const SiteRecipe& recipe) {
  LaneGrid lanes;
  lanes.xs = Lines(recipe.yard_size_m.x(), recipe.bay_m.x());
  lanes.ys = Lines(recipe.yard_size_m.y(), recipe.bay_m.y());
  return lanes;
}

Drives PlanDrives(const SiteRecipe& recipe, const LaneGrid& lanes, Rng* rng,
                  const std::function<double(const std::vector<V2>&)>& driven_a_m) {
  Drives drives;
  Walker walker(lanes, rng);
  const int start_side = std::min(3, static_cast<int>(rng->Uniform(0.0, 4.0)));
  const Gate entry = DrawGate(lanes, start_side, rng);
  drives.gates.push_back(entry);
  const V2 entry_node = lanes.Node(entry.i, entry.j);
  drives.start = entry.fence_point + kApproachM * entry.outward;
  drives.start_heading = -entry.outward;
  drives.roads.push_back({drives.start, entry_node});
  std::vector<V2>& a = drives.route_a;
  a = {drives.start};
  walker.DriveOff({drives.start, entry_node}, &a);
  int node = walker.Index(entry.i, entry.j), previous = -1;
  // Spur and the lanes share the drive's length (the spur is driven out and back).
  const double spur_m = recipe.featureless_m > 0.0
                            ? 2.0 * (kLaneInsetM + recipe.featureless_m) + 4.0 * kSpurLoopM
                            : 0.0;
  const double lanes_m = std::max(30.0, recipe.route_a_m - spur_m);
  if (recipe.featureless_m > 0.0) {
    const int spur_side = (start_side + 1 + static_cast<int>(rng->Uniform(0.0, 3.0))) % 4;
    const Gate spur = DrawGate(lanes, spur_side, rng);
    drives.gates.push_back(spur);
    walker.Walk(0.4 * lanes_m, &node, &previous, &a);
    walker.GoTo(walker.Index(spur.i, spur.j), &node, &previous, &a);
    // Out along the spur, round a teardrop loop at its end, and back the same way.
    const V2 gate_node = lanes.Node(spur.i, spur.j);
    const V2 side(-spur.outward.y(), spur.outward.x());
    const V2 far = spur.fence_point + recipe.featureless_m * spur.outward;
    const V2 loop_a = far + kSpurLoopM * spur.outward + 0.75 * kSpurLoopM * side;
    const V2 loop_b = far + kSpurLoopM * spur.outward - 0.75 * kSpurLoopM * side;
    walker.DriveOff({gate_node, far, loop_a, loop_b, far, gate_node}, &a);
    drives.roads.push_back({gate_node, far});
    drives.roads.push_back({far, loop_a});
    drives.roads.push_back({loop_a, loop_b});
    drives.roads.push_back({loop_b, far});
    previous = -1;  // back in from outside: every lane is ahead
    walker.Walk(0.6 * lanes_m, &node, &previous, &a);
  } else {
    walker.Walk(lanes_m, &node, &previous, &a);
  }
  a = Simplified(a);
  // The localization drive keeps to lanes the mapping drive completed (the map covers
  // them) and ends early where those lanes end.
  const Edges covered = walker.ReachedWithin(driven_a_m(a));
  drives.route_b.clear();
  if (covered.empty()) {  // the mapping drive never completed a lane: drive its approach
    drives.route_b = {drives.start, entry_node};
    return drives;
  }
  Walker b_walker(lanes, rng, &covered);
  node = b_walker.NodeOf(covered);
  previous = -1;
  drives.route_b = {walker.Position(node)};
  b_walker.Walk(recipe.route_b_m, &node, &previous, &drives.route_b);
  drives.route_b = Simplified(drives.route_b);
  return drives;
}

}  // namespace hylo::sim::scenario_site
