#pragma once
// The node's private parameters (~name), read once at start. Everything about the sensors and
// the estimator comes from the run configuration YAML (~config), the same file the CLI takes.

#include <ros/node_handle.h>

#include <string>

#include "input_queue.h"
#include "node_outputs.h"

namespace hylo::rosnode {

struct NodeParams {
  std::string config_path;             ///< ~config: run configuration YAML (required)
  std::string prior_map;               ///< ~prior_map: PCD/PLY in the map frame; "" = SLAM
  std::string initial_guess;           ///< ~initial_guess: "x y z roll pitch yaw" (m, deg) or
                                       ///< 16 numbers (registration/pose_guess.h) of the base
                                       ///< (IMU) in the map frame; "" = the config's
                                       ///< localization.initial_guess, and when that is
                                       ///< empty too, a global start (the whole map searched)
  std::string costmap;                 ///< ~costmap: map_server YAML (hylo traversability)
  std::string inspection_map;          ///< ~inspection_map: crafted map (PCD/PLY/LAS, map
                                       ///< frame) for ~plan_inspection; "" = no service
  std::string inspection_costmap;      ///< ~inspection_costmap: `hylo traversability` folder
  std::string inspection_targets;      ///< ~inspection_targets: targets CSV/YAML (map frame)
  std::string save_map_path = "hylo_map.pcd";  ///< ~save_map_path: where ~save_map writes;
                                       ///< read again at every call (rosparam set works)
  double registered_scan_voxel_m = -1; ///< ~registered_scan_voxel: voxel of the published
                                       ///< registered scan, m; < 0 = output.dense_map_voxel_m
  InputQueueOptions queue;             ///< ~queue_scans, ~queue_imu
  OutputOptions outputs;               ///< ~map_voxel, ~map_period, ~max_path_poses
  bool IsValid(std::string* why) const;
};

/// Reads the parameters from the private handle; throws std::runtime_error naming the
/// parameter when one is missing or invalid.
NodeParams ReadNodeParams(const ros::NodeHandle& private_nh);

}  // namespace hylo::rosnode
