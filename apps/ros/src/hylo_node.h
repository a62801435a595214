#pragma once
// The hylo ROS1 node: live topics in, the odometry pipeline on a worker thread, REP-105
// outputs. Callbacks only decode and enqueue (InputQueue, bounded); the worker owns the
// pipeline, so services that need it post a request and the worker answers it between scans.
//
//   subscribes  <lidar.topic> PointCloud2, <imu.topic> Imu, /initialpose
//   publishes   ~odometry, /tf, ~path, ~registered_scan, ~map_cloud (latched), ~health,
//               ~costmap (latched, when ~costmap is given)
//   services    ~relocalize (nav_msgs/SetMap: initial_pose is the guess, map is ignored),
//               ~global_localize (std_srvs/Trigger: forget the pose, search the whole prior
//               map while moving), ~save_map (std_srvs/Trigger: writes ~save_map_path),
//               ~plan_inspection (nav_msgs/GetPlan, when ~inspection_* are given: the
//               inspection route from request.start, or the current pose; inspection_service.h)

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <nav_msgs/GetPlan.h>
#include <nav_msgs/SetMap.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include <Eigen/Geometry>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "health.h"
#include "hylo/config/run_config.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/run/session.h"
#include "input_queue.h"
#include "inspection_service.h"
#include "node_outputs.h"
#include "node_params.h"

namespace hylo::rosnode {

class HyloNode {
 public:
  /// Loads the configuration, the prior map and the costmap; throws std::runtime_error
  /// naming the file and reason when one cannot be used.
  HyloNode(ros::NodeHandle nh, ros::NodeHandle private_nh, const NodeParams& params);

  /// The worker loop: runs until ros::ok() turns false.
  void Run();

 private:
  void OnCloud(const sensor_msgs::PointCloud2::ConstPtr& msg);
  void OnImu(const sensor_msgs::Imu::ConstPtr& msg);
  void OnInitialPose(const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& msg);
  bool OnRelocalize(nav_msgs::SetMap::Request& request, nav_msgs::SetMap::Response& response);
  bool OnGlobalLocalize(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool OnSaveMap(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool OnPlanInspection(nav_msgs::GetPlan::Request& request, nav_msgs::GetPlan::Response& response);
  /// Posts `job` to the worker and fills `response` with its answer (or its exception).
  void AskWorker(std::vector<std::shared_ptr<std::promise<std::string>>>* queue,
                 std_srvs::Trigger::Response* response);

  /// Queues a relocalization around a world-frame pose; false with *why when impossible.
  bool RequestRelocalization(const std::string& frame_id, const Eigen::Isometry3d& T_world_imu,
                             std::string* why);
  void LoadPriorMap();
  /// Worker side: pending relocalization and save-map requests.
  void ServeRequests();
  void ReportEvents();
  void PublishHealth(const odometry::ScanResult* last);
  /// Writes the current map (world frame) to `path`; returns a one-line summary.
  std::string SaveMap(const std::string& path);

  ros::NodeHandle nh_, private_nh_;
  NodeParams params_;
  config::RunConfig config_;
  FrameNames frames_;
  run::Session session_;  ///< the pipeline and the prior map's local origin
  odometry::OdometryPipeline& pipeline_;  ///< session_'s
  InputQueue input_;
  NodeOutputs outputs_;
  ros::Subscriber cloud_sub_, imu_sub_, initial_pose_sub_;
  ros::ServiceServer relocalize_srv_, global_localize_srv_, save_map_srv_, plan_inspection_srv_;
  std::unique_ptr<const InspectionService> inspection_;  ///< none without ~inspection_*

  // Callback side (lidar callback only).
  logs::PointTimeConvention convention_;
  bool lidar_extrinsic_published_ = false;
  std::size_t undecodable_scans_ = 0;

  // Requests from callbacks to the worker.
  std::mutex request_mutex_;
  std::optional<Eigen::Isometry3d> relocalization_request_;  ///< T_map_imu (local frame)
  std::vector<std::shared_ptr<std::promise<std::string>>> save_requests_;
  std::vector<std::shared_ptr<std::promise<std::string>>> global_requests_;
  std::optional<Eigen::Isometry3d> last_valid_T_world_imu_;  ///< the newest valid pose

  // Worker side.
  bool relocalization_pending_ = false;
  std::size_t events_seen_ = 0;
  std::string last_event_;
  bool failure_reported_ = false;
  HealthReport health_;  ///< the last report (its scan fields persist between scans)
  ros::WallTime last_health_;
};

}  // namespace hylo::rosnode
