#include "node_params.h"

#include <algorithm>
#include <stdexcept>

namespace hylo::rosnode {

bool NodeParams::IsValid(std::string* why) const {
  if (config_path.empty()) {
    *why = "~config is empty: the run configuration YAML is required";
    return false;
  }
  const int inspection_inputs =
      !inspection_map.empty() + !inspection_costmap.empty() + !inspection_targets.empty();
  if (inspection_inputs != 0 && inspection_inputs != 3) {
    *why =
        "~inspection_map, ~inspection_costmap and ~inspection_targets go together (all three "
        "for ~plan_inspection, or none)";
    return false;
  }
  std::string sub;
  if (!queue.IsValid(&sub) || !outputs.IsValid(&sub)) {
    *why = sub;
    return false;
  }
  return true;
}

NodeParams ReadNodeParams(const ros::NodeHandle& nh) {
  NodeParams p;
  nh.param<std::string>("config", p.config_path, p.config_path);
  nh.param<std::string>("prior_map", p.prior_map, p.prior_map);
  nh.param<std::string>("initial_guess", p.initial_guess, p.initial_guess);
  nh.param<std::string>("costmap", p.costmap, p.costmap);
  nh.param<std::string>("save_map_path", p.save_map_path, p.save_map_path);
  nh.param<std::string>("inspection_map", p.inspection_map, p.inspection_map);
  nh.param<std::string>("inspection_costmap", p.inspection_costmap, p.inspection_costmap);
  nh.param<std::string>("inspection_targets", p.inspection_targets, p.inspection_targets);
  nh.param("registered_scan_voxel", p.registered_scan_voxel_m, p.registered_scan_voxel_m);
  int queue_scans = static_cast<int>(p.queue.max_scans);
  int queue_imu = static_cast<int>(p.queue.max_imu);
  int max_path = static_cast<int>(p.outputs.max_path_poses);
  nh.param("queue_scans", queue_scans, queue_scans);
  nh.param("queue_imu", queue_imu, queue_imu);
  nh.param("max_path_poses", max_path, max_path);
  p.queue.max_scans = static_cast<std::size_t>(std::max(queue_scans, 0));
  p.queue.max_imu = static_cast<std::size_t>(std::max(queue_imu, 0));
  p.outputs.max_path_poses = static_cast<std::size_t>(std::max(max_path, 0));
  nh.param("map_voxel", p.outputs.map_voxel_m, p.outputs.map_voxel_m);
  nh.param("map_period", p.outputs.map_period_s, p.outputs.map_period_s);
  std::string why;
  if (!p.IsValid(&why)) throw std::runtime_error("hylo_node parameters: " + why);
  return p;
}

}  // namespace hylo::rosnode
