#pragma once
// The node's ~plan_inspection service (nav_msgs/GetPlan): `hylo inspect`'s route from a start
// to every target's viewpoint (and back), as a nav_msgs/Path in the map frame. The crafted map,
// the costmap folder and the targets are read once at start (~inspection_map,
// ~inspection_costmap, ~inspection_targets, in the map frame: the prior map file's); the
// options are the run configuration's `inspection:` section. request.start is where the
// route begins: a pose in the map frame, or, with an empty frame_id, the node's current pose
// (refused while there is no valid one). request.goal and tolerance are not used: the goals
// are the targets. Planning (seconds) runs on the service's callback thread, never on the
// pipeline's.

#include <nav_msgs/Path.h>
#include <ros/time.h>

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "hylo/run/inspection_run.h"

namespace hylo::rosnode {

/// Where a route starts (map frame, m): `requested_xy` when `frame_id` is the map frame, the
/// current pose when `frame_id` is empty; none with *why otherwise (another frame, or no valid
/// pose yet).
std::optional<Eigen::Vector2d> ResolveStart(const std::string& frame_id,
                                            const Eigen::Vector2d& requested_xy,
                                            const std::optional<Eigen::Isometry3d>& T_world_imu,
                                            const std::string& map_frame, std::string* why);

/// The route's corners (map frame, m) as a Path in `frame_id`: z = 0, each pose facing the
/// next corner (the last keeps the one before).
nav_msgs::Path ToPathMsg(const std::vector<Eigen::Vector2d>& route_map, const std::string& frame_id,
                         const ros::Time& stamp);

class InspectionService {
 public:
  /// Reads the inputs; throws std::runtime_error naming the file when one cannot be used, and
  /// std::invalid_argument for invalid options.
  InspectionService(const std::string& map, const std::string& costmap, const std::string& targets,
                    const inspection::InspectionOptions& options);

  /// Plans from `start_map`; false with *why when the planner refuses (a start off the free
  /// space). A one-line summary of the plan goes to *summary.
  bool Plan(const Eigen::Vector2d& start_map, std::vector<Eigen::Vector2d>* route_map,
            std::string* summary) const;

  std::size_t num_targets() const { return inputs_.targets_local.size(); }

 private:
  run::InspectionInputs inputs_;
  inspection::InspectionOptions options_;
};

}  // namespace hylo::rosnode
