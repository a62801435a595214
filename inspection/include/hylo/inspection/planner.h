#pragma once
// Inspection planning: from the crafted map and its traversability costmap to where the robot
// must stand to see each target, and the route there (Alamanos et al.: "raycasting between
// points of interest and the ground" for "the visibility region of points of interest").
//   1. where the robot can stand: free and cost cells away from lethal ones (robot radius);
//   2. what it can reach: Dijkstra on the costmap from the start;
//   3. the map as voxels, inflated by the clearance, over the box sight lines can cross;
//   4. per target, every standable cell in range and viewing direction: are the sight lines
//      from the camera on it clear (3-D DDA)?
//   5. per target, the best visible and reachable cell (viewpoint_selection.h), or the
//      reason there is none (occluded, unreachable);
//   6. travel costs between the viewpoints (Dijkstra from each), the order of visits
//      (tour.h), and the route on the costmap (A* per leg, straightened where the straight
//      line stays on passable cells: route_smoothing.h).
// Everything is in the grid's local frame; the caller converts (hylo::io reads and writes
// the map frame). Single-threaded; no file I/O.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/inspection/cost_grid_search.h"
#include "hylo/inspection/target.h"
#include "hylo/inspection/tour.h"
#include "hylo/inspection/viewpoint_selection.h"
#include "hylo/inspection/visibility.h"
#include "hylo/terrain/grid_map.h"
#include "hylo/terrain/traversability_cost.h"

namespace hylo::inspection {

struct InspectionOptions {
  VisibilityOptions visibility;     ///< camera, ranges, voxels, clearance
  SearchOptions search;             ///< robot radius, cost weight of paths
  ViewpointOptions viewpoint;       ///< how the viewpoint is chosen
  TourOptions tour;                 ///< closed or open, exact up to how many stops
  double start_snap_radius_m = 3.0; ///< a start off the passable cells moves to the nearest
                                    ///< one within this distance, m

  /// True when usable; otherwise `why` names the field (with its section), value, constraint.
  bool IsValid(std::string* why) const;
};

/// What became of one target.
struct TargetPlan {
  TargetStatus status = TargetStatus::kOccluded;
  std::string reason;                    ///< one line: why occluded or unreachable
  std::size_t candidate_cells = 0;       ///< standable cells in range and view direction
  std::size_t visible_cells = 0;         ///< of those, cells that see it
  std::size_t reachable_visible_cells = 0;
  // Planned targets only:
  std::size_t view_cell = 0;                         ///< grid index of the viewpoint
  Eigen::Vector3d camera = Eigen::Vector3d::Zero();  ///< camera position there, local, m
  double range_m = 0.0;                              ///< camera to target centre, m
  double view_angle_deg = 0.0;                       ///< ViewAngleDeg
  int order = 0;                   ///< 1-based place in the visits, 0 when not planned
  int stop = -1;                   ///< index into InspectionPlan::stops
  double leg_length_m = 0.0;       ///< route length from the previous stop to this one, m
  double along_route_m = 0.0;      ///< route length from the start to this stop, m
};

/// A place the robot stops at to look: one viewpoint cell, one or more targets.
struct RouteStop {
  std::size_t cell = 0;          ///< grid index
  std::vector<int> targets;      ///< indices into the targets given
  double leg_length_m = 0.0;     ///< route length from the previous stop (along the
                                 ///< waypoints), m
  double leg_cost = 0.0;         ///< weighted cost of that leg's cell path
};

/// A corner of the route: between two corners the robot drives straight, over passable cells
/// only (route_smoothing.h).
struct Waypoint {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  ///< local, m (a cell centre)
  int stop = -1;                                 ///< index into stops where the robot stops
};

struct InspectionSummary {
  std::size_t passable_cells = 0, reachable_cells = 0;
  std::size_t planned = 0, occluded = 0, unreachable = 0;
  OccupancySummary occupancy;
  TourMethod tour_method = TourMethod::kTrivial;
  double route_length_m = 0.0;   ///< whole route along the waypoints, m
  double route_cost = 0.0;       ///< weighted cost of the cell paths (what the tour minimised)
  double seconds_occupancy = 0.0, seconds_reach = 0.0, seconds_visibility = 0.0,
         seconds_travel_costs = 0.0, seconds_tour = 0.0, seconds_route = 0.0;
};

struct InspectionPlan {
  std::size_t start_cell = 0;                  ///< where the route begins (snapped)
  std::vector<TargetPlan> targets;             ///< one per target, in the order given
  std::vector<TargetVisibility> visibility;    ///< one per target
  std::vector<RouteStop> stops;                ///< in visiting order
  std::vector<std::size_t> route_cells;        ///< every cell of the legs' cell paths
  std::vector<Waypoint> waypoints;             ///< the route's corners, start first
  std::vector<uint8_t> passable;               ///< per cell (PassableCells)
  std::vector<double> reach_cost;              ///< per cell from the start, +inf: unreachable
  std::vector<float> camera_z;                 ///< per cell, local, NaN where not standable
  InspectionSummary summary;
};

/// The start is not on the costmap's free space (nor within start_snap_radius_m of it).
class StartNotPassable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Called as work progresses: stage name ("occupancy", "reach", "visibility", "travel
/// costs", "route"), items done, items in the stage.
using InspectionProgress =
    std::function<void(const std::string& stage, std::size_t done, std::size_t total)>;

/// Plans the inspection. `grid` needs the layers elevation (local heights) and cost, with
/// `classes` per cell; `map_local` and `targets` are in the grid's local frame; `start` is a
/// local xy. Throws std::invalid_argument for invalid options or targets (naming the target)
/// or an id given twice, StartNotPassable when the start is not within start_snap_radius_m of
/// a passable cell, and std::runtime_error when the occupancy grid would be too large.
InspectionPlan PlanInspection(const PointCloud& map_local, const terrain::GridMap& grid,
                              const std::vector<terrain::CellClass>& classes,
                              const std::vector<Target>& targets, const Eigen::Vector2d& start,
                              const InspectionOptions& options,
                              const InspectionProgress& progress = {});

}  // namespace hylo::inspection
