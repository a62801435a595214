// The route part of PlanInspection: stops, travel costs, tour, legs, corners.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "hylo/common/check.h"
#include "hylo/inspection/route_smoothing.h"
#include "planner_steps.h"

namespace hylo::inspection {
namespace {

using Clock = std::chrono::steady_clock;
double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The places to go: node 0 is the start; then each distinct viewpoint cell, with its targets.
struct Nodes {
  std::vector<std::size_t> cells;
  std::vector<std::vector<int>> targets;
};

Nodes CollectNodes(const InspectionPlan& plan) {
  Nodes nodes;
  nodes.cells.push_back(plan.start_cell);
  nodes.targets.emplace_back();
  std::map<std::size_t, int> index{{plan.start_cell, 0}};
  for (std::size_t i = 0; i < plan.targets.size(); ++i) {
    const TargetPlan& t = plan.targets[i];
    if (t.status != TargetStatus::kPlanned) continue;
    const auto [it, added] = index.emplace(t.view_cell, static_cast<int>(nodes.cells.size()));
    if (added) {
      nodes.cells.push_back(t.view_cell);
      nodes.targets.emplace_back();
    }
    nodes.targets[it->second].push_back(static_cast<int>(i));
  }
  return nodes;
}

// Symmetric travel costs: one Dijkstra per node, stopped once the later nodes are settled.
CostMatrix TravelCosts(const CostGrid& costs, const std::vector<std::size_t>& cells,
                       const InspectionProgress& progress) {
  const int n = static_cast<int>(cells.size());
  CostMatrix matrix = CostMatrix::Zero(n, n);
  for (int i = 0; i + 1 < n; ++i) {
    if (progress) progress("travel costs", i, n - 1);
    const std::vector<std::size_t> later(cells.begin() + i + 1, cells.end());
    const std::vector<double> d = costs.Distances(cells[i], later);
    for (int j = i + 1; j < n; ++j) {
      HYLO_CHECK(std::isfinite(d[cells[j]]), "viewpoints are reachable from the start");
      matrix(i, j) = matrix(j, i) = d[cells[j]];
    }
  }
  if (progress) progress("travel costs", n - 1, n - 1);
  return matrix;
}

}  // namespace

void PlanRoute(const CostGrid& costs, const TourOptions& options, InspectionPlan* plan,
               const InspectionProgress& progress) {
  InspectionSummary& summary = plan->summary;
  const Nodes nodes = CollectNodes(*plan);
  auto t0 = Clock::now();
  const CostMatrix matrix = TravelCosts(costs, nodes.cells, progress);
  summary.seconds_travel_costs = SecondsSince(t0);
  t0 = Clock::now();
  std::vector<int> order = PlanTour(matrix, options, &summary.tour_method);
  if (options.return_to_start && order.size() > 1) order.push_back(0);
  summary.seconds_tour = SecondsSince(t0);

  t0 = Clock::now();
  const terrain::GridGeometry& g = costs.geometry();
  const auto waypoint = [&](std::size_t cell) {
    return Waypoint{g.CentreLocal(g.Col(cell), g.Row(cell)), -1};
  };
  plan->route_cells = {plan->start_cell};
  plan->waypoints = {waypoint(plan->start_cell)};
  double along = 0.0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (progress) progress("route", k, order.size());
    RouteStop stop;
    stop.cell = nodes.cells[order[k]];
    stop.targets = k + 1 == order.size() && k > 0 && order[k] == 0 ? std::vector<int>{}
                                                                    : nodes.targets[order[k]];
    if (k > 0) {
      const GridPath leg = costs.ShortestPath(nodes.cells[order[k - 1]], stop.cell);
      HYLO_CHECK(leg.found(), "a leg between reachable cells");
      plan->route_cells.insert(plan->route_cells.end(), leg.cells.begin() + 1, leg.cells.end());
      const std::vector<std::size_t> corners = StraightenPath(costs, leg.cells);
      for (std::size_t c = 1; c < corners.size(); ++c) {
        plan->waypoints.push_back(waypoint(corners[c]));
        stop.leg_length_m += (plan->waypoints.back().xy - plan->waypoints.end()[-2].xy).norm();
      }
      stop.leg_cost = leg.cost;
      summary.route_length_m += stop.leg_length_m;
      summary.route_cost += leg.cost;
      along += stop.leg_length_m;
    }
    if (stop.targets.empty()) continue;  // the start (or the return to it) without a view
    const int stop_index = static_cast<int>(plan->stops.size());
    plan->waypoints.back().stop = stop_index;
    for (std::size_t j = 0; j < stop.targets.size(); ++j) {
      TargetPlan& t = plan->targets[stop.targets[j]];
      t.stop = stop_index;
      t.leg_length_m = j == 0 ? stop.leg_length_m : 0.0;
      t.along_route_m = along;
    }
    plan->stops.push_back(std::move(stop));
  }
  int order_number = 0;
  for (const RouteStop& stop : plan->stops) {
    for (const int i : stop.targets) plan->targets[i].order = ++order_number;
  }
  if (progress) progress("route", order.size(), order.size());
  summary.seconds_route = SecondsSince(t0);
}

}  // namespace hylo::inspection
