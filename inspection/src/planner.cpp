#include "hylo/inspection/planner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <stdexcept>

#include "hylo/common/check.h"
#include "hylo/common/option_checks.h"
#include "planner_steps.h"

namespace hylo::inspection {
namespace {

using Clock = std::chrono::steady_clock;
double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void CheckInputs(const terrain::GridMap& grid, const std::vector<terrain::CellClass>& classes,
                 const std::vector<Target>& targets, const InspectionOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("inspection options: " + why);
  if (!grid.HasLayer(terrain::layers::kElevation) || !grid.HasLayer(terrain::layers::kCost) ||
      classes.size() != grid.geometry().NumCells()) {
    throw std::invalid_argument("inspection: the grid needs elevation and cost layers and a class "
                                "per cell");
  }
  std::set<std::string> ids;
  for (const Target& t : targets) {
    if (!t.IsValid(&why)) throw std::invalid_argument("target '" + t.id + "': " + why);
    if (!ids.insert(t.id).second) throw std::invalid_argument("target '" + t.id + "' given twice");
  }
}

}  // namespace

bool InspectionOptions::IsValid(std::string* why) const {
  return CheckSection(visibility, "visibility", why) && CheckSection(search, "search", why) &&
         CheckSection(viewpoint, "viewpoint", why) && CheckSection(tour, "tour", why) &&
         CheckNonNegative("start_snap_radius_m", start_snap_radius_m, why);
}

InspectionPlan PlanInspection(const PointCloud& map_local, const terrain::GridMap& grid,
                              const std::vector<terrain::CellClass>& classes,
                              const std::vector<Target>& targets, const Eigen::Vector2d& start,
                              const InspectionOptions& options,
                              const InspectionProgress& progress) {
  CheckInputs(grid, classes, targets, options);
  const auto report = [&](const char* stage, std::size_t done, std::size_t total) {
    if (progress) progress(stage, done, total);
  };
  const terrain::GridGeometry& geometry = grid.geometry();
  InspectionPlan plan;
  InspectionSummary& summary = plan.summary;

  // 1-2. Where the robot can stand, and what it can reach from the start.
  auto t0 = Clock::now();
  report("reach", 0, 1);
  plan.passable = PassableCells(geometry, classes, options.search.robot_radius_m);
  const CostGrid costs(geometry, plan.passable, grid.Layer(terrain::layers::kCost),
                       options.search.cost_weight);
  plan.start_cell = SnapStart(costs, start, options.start_snap_radius_m);
  plan.reach_cost = costs.Distances(plan.start_cell);
  std::vector<uint8_t> reachable(plan.reach_cost.size());
  for (std::size_t i = 0; i < reachable.size(); ++i) reachable[i] = std::isfinite(plan.reach_cost[i]);
  summary.passable_cells = std::count(plan.passable.begin(), plan.passable.end(), 1);
  summary.reachable_cells = std::count(reachable.begin(), reachable.end(), 1);
  plan.camera_z = CameraHeights(grid, plan.passable, options.visibility.camera_height_m);
  summary.seconds_reach = SecondsSince(t0);
  report("reach", 1, 1);

  // 3. The map as voxels over the box the sight lines can cross.
  t0 = Clock::now();
  report("occupancy", 0, 1);
  std::vector<TargetShape> shapes;
  for (const Target& t : targets) shapes.push_back(ShapeOf(t, options.visibility));
  Eigen::Vector3d box_min, box_max;
  SightLineBox(shapes, geometry, plan.camera_z, &box_min, &box_max);
  const OccupancyGrid occupancy =
      OccupancyGrid::Build(map_local, box_min, box_max, options.visibility.occupancy);
  summary.occupancy = occupancy.summary();
  summary.seconds_occupancy = SecondsSince(t0);
  report("occupancy", 1, 1);

  // 4-5. Per target: the cells that see it, and the best reachable one.
  t0 = Clock::now();
  for (std::size_t i = 0; i < targets.size(); ++i) {
    report("visibility", i, targets.size());
    plan.visibility.push_back(ComputeVisibility(shapes[i], geometry, plan.camera_z, occupancy));
    const Viewpoint view =
        SelectViewpoint(shapes[i], plan.visibility.back(), geometry, plan.camera_z,
                        grid.Layer(terrain::layers::kCost), reachable, options.viewpoint);
    plan.targets.push_back(Judge(shapes[i], plan.visibility.back(), view));
  }
  report("visibility", targets.size(), targets.size());
  summary.seconds_visibility = SecondsSince(t0);

  // 6. The order of visits and the route.
  PlanRoute(costs, options.tour, &plan, progress);
  for (const TargetPlan& t : plan.targets) {
    summary.planned += t.status == TargetStatus::kPlanned;
    summary.occluded += t.status == TargetStatus::kOccluded;
    summary.unreachable += t.status == TargetStatus::kUnreachable;
  }
  return plan;
}

}  // namespace hylo::inspection
