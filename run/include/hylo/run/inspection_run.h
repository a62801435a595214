#pragma once
// Inspection planning from files, as every front end runs it (`hylo inspect`, `hylo demo`,
// hylo.inspect in Python, the ROS node's ~plan_inspection service): read the crafted map, the
// costmap folder and the targets once, move them to the costmap's local frame, plan from a
// start in the map frame, and write the plan's files (hylo/io/inspection_io.h). The planning
// itself is inspection::PlanInspection; this layer only converts frames, names inputs in
// errors and in the summary, and applies a front end's option overrides.

#include <Eigen/Core>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/inspection/planner.h"
#include "hylo/io/costmap_io.h"
#include "hylo/io/json.h"

namespace hylo::run {

/// The options a front end may set beside a configuration's `inspection:` section (the
/// command's flags, the Python keywords); unset ones keep the section's value.
struct InspectionOverrides {
  std::optional<double> camera_height_m;  ///< visibility.camera_height_m
  std::optional<double> min_range_m;      ///< visibility.min_range_m
  std::optional<double> max_range_m;      ///< visibility.max_range_m
  std::optional<double> clearance_m;      ///< visibility.occupancy.clearance_m
  std::optional<double> voxel_m;          ///< visibility.occupancy.voxel_size_m
  std::optional<double> robot_radius_m;   ///< search.robot_radius_m
  std::optional<bool> return_to_start;    ///< tour.return_to_start
};

/// `options` with `overrides` applied; throws std::invalid_argument naming the field, its value
/// and the constraint when the result is not valid.
inspection::InspectionOptions WithOverrides(inspection::InspectionOptions options,
                                            const InspectionOverrides& overrides);

/// What a plan is made from, read once (the ROS node plans from it again for every start).
struct InspectionInputs {
  std::string map_path, costmap_dir, targets_path;  ///< as given (the summary names them)
  io::CostmapLayers costmap;  ///< its grid's origin_world is the local frame's origin
  PointCloud map_local;       ///< the crafted map, local frame
  std::vector<inspection::Target> targets_local;  ///< local frame, in the file's order

  const Eigen::Vector3d& origin_world() const { return costmap.grid.geometry().origin_world; }
};

/// Reads the three inputs (map frame on disk). Throws std::runtime_error naming the file and
/// the reason: unreadable, a map without points, targets that cannot be used (io/targets_io.h).
InspectionInputs ReadInspectionInputs(const std::string& map_path, const std::string& costmap_dir,
                                      const std::string& targets_path);

/// A plan and its summary (io::InspectionPlanJson + the input paths).
struct InspectionRun {
  inspection::InspectionPlan plan;  ///< local frame
  io::Json summary;                 ///< map frame
};

/// The start given to the planner is not on the costmap's free space; the message names the
/// start in the map frame.
class InspectionStartError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Plans from `inputs` with the route starting at `start_map` (xy in the map frame, m).
/// Throws std::invalid_argument for invalid options or targets, InspectionStartError when the
/// start is off the passable cells, std::runtime_error when the occupancy grid is too large.
InspectionRun PlanInspectionRun(const InspectionInputs& inputs, const Eigen::Vector2d& start_map,
                                const inspection::InspectionOptions& options,
                                const inspection::InspectionProgress& progress = {});

/// Writes plan.csv, route.csv, visibility/, plan.png and summary.json into `dir`; returns the
/// written paths (also listed in summary.json's "outputs").
std::vector<std::string> WriteInspectionRun(const std::string& dir, const InspectionInputs& inputs,
                                            const InspectionRun& run);

/// The route's corners (route.csv's x, y) in the map frame, m, in driving order.
std::vector<Eigen::Vector2d> RouteMapFrame(const InspectionInputs& inputs,
                                           const InspectionRun& run);

}  // namespace hylo::run
