#pragma once
// The files of an inspection plan (`hylo inspect --out DIR`), in the map frame (the plan's
// local coordinates + the grid's origin_world):
//   plan.csv       one row per target, in the order given:
//                    target_id,status,view_x,view_y,view_z,order,path_length_m,
//                    along_route_m,range_m,view_angle_deg,visible_cells,reason
//                  view_* = the camera's position at the viewpoint; order = 1-based place in
//                  the visits; path_length_m = length of the route leg that arrives there
//                  (0 for a second target seen from the same stop); along_route_m = route
//                  length from the start; empty cells for targets not planned; reason says
//                  why a target is occluded or unreachable (quoted)
//   route.csv      the route's corners in driving order: x,y,stop (stop = the ids of the
//                  targets seen there, ';'-separated, empty elsewhere); straight runs of the
//                  costmap path between corners cross only passable cells
//   visibility/<id>.asc  per target, an ESRI ASCII grid on the costmap's cells, cut to the
//                  target's range: 0 in range but the map blocks the view, 1 sees it but not
//                  reachable, 2 sees it and reachable, 3 the chosen viewpoint; NODATA where
//                  the robot cannot stand or out of range
//   plan.png       the costmap's colours (costmap_io.h) with the route (blue), viewpoints
//                  (white squares) and their sight lines (white), targets as crosses: planned
//                  cyan, occluded magenta, unreachable orange; the start a blue square
//   summary.json   InspectionPlanJson + the files written
// Every file is written atomically.

#include <string>
#include <vector>

#include "hylo/inspection/planner.h"
#include "hylo/io/costmap_io.h"
#include "hylo/io/json.h"

namespace hylo::io {

/// Every option of the planner.
Json InspectionOptionsJson(const inspection::InspectionOptions& options);

/// Counts, route, timings, occupancy and per-target results; positions in the map frame.
Json InspectionPlanJson(const inspection::InspectionPlan& plan,
                        const std::vector<inspection::Target>& targets_local,
                        const terrain::GridGeometry& geometry,
                        const inspection::InspectionOptions& options);

/// Writes plan.csv, route.csv, visibility/, plan.png and summary.json (`summary` with an
/// "outputs" list added) into `dir` (created if missing); returns the written paths. Throws
/// std::runtime_error naming the file or folder that cannot be written.
std::vector<std::string> WriteInspectionFiles(const std::string& dir,
                                              const inspection::InspectionPlan& plan,
                                              const std::vector<inspection::Target>& targets_local,
                                              const CostmapLayers& costmap, Json summary);

/// The PNG described above, as file bytes (pixels scaled up so the longer side has >= 1000 px,
/// at most 4 per cell).
std::string PlanPng(const inspection::InspectionPlan& plan,
                    const std::vector<inspection::Target>& targets_local,
                    const CostmapLayers& costmap);

}  // namespace hylo::io
