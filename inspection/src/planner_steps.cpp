#include "planner_steps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace hylo::inspection {
namespace {

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof(text), format, a, b, c);
  return text;
}

}  // namespace

std::size_t SnapStart(const CostGrid& costs, const Eigen::Vector2d& start, double snap_radius_m) {
  const terrain::GridGeometry& g = costs.geometry();
  const auto under = g.CellOfLocal(start.x(), start.y());
  if (under && costs.Passable(g.Index(under->x(), under->y()))) return g.Index(under->x(), under->y());
  double nearest = std::numeric_limits<double>::infinity();
  std::size_t best = 0;
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    if (!costs.Passable(cell)) continue;
    const double d = (g.CentreLocal(g.Col(cell), g.Row(cell)) - start).norm();
    if (d < nearest) nearest = d, best = cell;
  }
  if (nearest <= snap_radius_m) return best;
  if (!std::isfinite(nearest)) throw StartNotPassable("the costmap has no passable cell");
  throw StartNotPassable(Format("the start is %.2f m from the nearest passable cell (%.2f m "
                                  "allowed): not on the costmap's free space",
                                  nearest, snap_radius_m));
}

std::vector<float> CameraHeights(const terrain::GridMap& grid, const std::vector<uint8_t>& passable,
                                 double camera_height_m) {
  const std::vector<float>& elevation = grid.Layer(terrain::layers::kElevation);
  std::vector<float> z(elevation.size(), std::nanf(""));
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (passable[i] && std::isfinite(elevation[i]))
      z[i] = static_cast<float>(elevation[i] + camera_height_m);
  }
  return z;
}

void SightLineBox(const std::vector<TargetShape>& shapes, const terrain::GridGeometry& geometry,
                  const std::vector<float>& camera_z, Eigen::Vector3d* box_min,
                  Eigen::Vector3d* box_max) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const Eigen::Vector2d grid_lo = geometry.corner_local;
  const Eigen::Vector2d grid_hi =
      grid_lo + geometry.resolution_m * Eigen::Vector2d(geometry.width, geometry.height);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = -lo;
  for (const TargetShape& s : shapes) {
    for (int k = 0; k < s.num_samples; ++k) {
      lo = lo.cwiseMin(s.samples[k]);
      hi = hi.cwiseMax(s.samples[k]);
    }
    // Cameras: grid cells within range of the centre.
    const Eigen::Vector2d reach = Eigen::Vector2d::Constant(s.max_range_m);
    const Eigen::Vector2d cameras_lo = (s.centre.head<2>() - reach).cwiseMax(grid_lo);
    const Eigen::Vector2d cameras_hi = (s.centre.head<2>() + reach).cwiseMin(grid_hi);
    if ((cameras_lo.array() > cameras_hi.array()).any()) continue;  // no cell in range
    lo.head<2>() = lo.head<2>().cwiseMin(cameras_lo);
    hi.head<2>() = hi.head<2>().cwiseMax(cameras_hi);
  }
  for (const float z : camera_z) {
    if (std::isnan(z)) continue;
    lo.z() = std::min(lo.z(), static_cast<double>(z));
    hi.z() = std::max(hi.z(), static_cast<double>(z));
  }
  *box_min = lo;
  *box_max = hi;
}

TargetPlan Judge(const TargetShape& shape, const TargetVisibility& visibility,
                 const Viewpoint& view) {
  TargetPlan t;
  t.candidate_cells = visibility.cells.size();
  t.visible_cells = visibility.visible_cells;
  t.reachable_visible_cells = view.reachable_visible_cells;
  if (view.found) {
    t.status = TargetStatus::kPlanned;
    t.view_cell = view.cell;
    t.camera = view.camera;
    t.range_m = view.range_m;
    t.view_angle_deg = view.view_angle_deg;
    return t;
  }
  if (t.candidate_cells == 0) {
    t.status = TargetStatus::kOccluded;
    t.reason = Format("no cell the robot can stand on lies %.1f-%.1f m from it", shape.min_range_m,
                      shape.max_range_m);
    if (shape.has_direction) t.reason += " in the required viewing direction";
  } else if (t.visible_cells == 0) {
    t.status = TargetStatus::kOccluded;
    t.reason = "the map blocks every sight line from the " + std::to_string(t.candidate_cells) +
               " cells in range";
  } else {
    t.status = TargetStatus::kUnreachable;
    t.reason = "seen from " + std::to_string(t.visible_cells) +
               " cells, none reachable from the start";
  }
  return t;
}

}  // namespace hylo::inspection
