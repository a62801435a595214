#pragma once
// The steps PlanInspection composes (planner.h reads like the algorithm; the details live
// here). Private to hylo::inspection.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "hylo/inspection/planner.h"

namespace hylo::inspection {

/// The passable cell nearest to `start` (local xy) within `snap_radius_m`, or the cell under
/// it when passable. Throws StartNotPassable when there is none, saying how far the nearest
/// passable cell is.
std::size_t SnapStart(const CostGrid& costs, const Eigen::Vector2d& start, double snap_radius_m);

/// Per cell: elevation + camera height where the robot can stand, NaN elsewhere.
std::vector<float> CameraHeights(const terrain::GridMap& grid, const std::vector<uint8_t>& passable,
                                 double camera_height_m);

/// The box every sight line lies in: targets' reach in xy (clipped to the grid), cameras'
/// and targets' heights in z. min > max when there is no target.
void SightLineBox(const std::vector<TargetShape>& shapes, const terrain::GridGeometry& geometry,
                  const std::vector<float>& camera_z, Eigen::Vector3d* box_min,
                  Eigen::Vector3d* box_max);

/// A target's status and reason from its visibility and chosen viewpoint.
TargetPlan Judge(const TargetShape& shape, const TargetVisibility& visibility,
                 const Viewpoint& view);

/// Travel costs between the start and the viewpoints, the order of visits, the route's
/// cells and corners, and each planned target's order and leg (route_planning.cpp).
void PlanRoute(const CostGrid& costs, const TourOptions& options, InspectionPlan* plan,
               const InspectionProgress& progress);

}  // namespace hylo::inspection
