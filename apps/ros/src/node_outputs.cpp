#include "node_outputs.h"

#include <geometry_msgs/TransformStamped.h>
#include <std_msgs/String.h>

#include "hylo/common/time.h"
#include "hylo/logs/ros_bridge.h"
#include "hylo/lie/isometry.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::rosnode {

bool OutputOptions::IsValid(std::string* why) const {
  if (!(map_voxel_m >= 0.0)) {
    *why = "map_voxel_m = " + std::to_string(map_voxel_m) + ": must be >= 0";
    return false;
  }
  if (!(map_period_s >= 0.0)) {
    *why = "map_period_s = " + std::to_string(map_period_s) + ": must be >= 0";
    return false;
  }
  if (max_path_poses < 1) {
    *why = "max_path_poses = 0: must be >= 1";
    return false;
  }
  return true;
}

NodeOutputs::NodeOutputs(ros::NodeHandle& nh, const FrameNames& frames,
                         const OutputOptions& options)
    : frames_(frames), options_(options) {
  odometry_ = nh.advertise<nav_msgs::Odometry>("odometry", 50);
  path_ = nh.advertise<nav_msgs::Path>("path", 1);
  scan_ = nh.advertise<sensor_msgs::PointCloud2>("registered_scan", 5);
  map_ = nh.advertise<sensor_msgs::PointCloud2>("map_cloud", 1, /*latch=*/true);
  health_ = nh.advertise<std_msgs::String>("health", 20);
  costmap_ = nh.advertise<nav_msgs::OccupancyGrid>("costmap", 1, /*latch=*/true);
  path_msg_.header.frame_id = frames_.map;
  cloud_frame_ = frames_.map;
}

namespace {

geometry_msgs::TransformStamped Stamped(const Eigen::Isometry3d& T, const ros::Time& stamp,
                                        const std::string& parent, const std::string& child) {
  geometry_msgs::TransformStamped msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = parent;
  msg.child_frame_id = child;
  msg.transform = ToTransformMsg(T);
  return msg;
}

}  // namespace

void NodeOutputs::SetOrigin(const Eigen::Vector3d& origin_world) {
  origin_world_ = origin_world;
  if (origin_world_.isZero()) return;
  cloud_frame_ = frames_.map + "_local";
  Eigen::Isometry3d T_map_local = Eigen::Isometry3d::Identity();
  T_map_local.translation() = origin_world_;
  static_tf_.sendTransform(Stamped(T_map_local, ros::Time::now(), frames_.map, cloud_frame_));
}

void NodeOutputs::PublishScan(const odometry::ScanResult& result) {
  const FramePoses poses = ComputeFramePoses(lie::ToIsometry(result.state.T_map_imu()),
                                             lie::ToIsometry(result.T_map_odom), origin_world_);
  const ros::Time stamp = logs::ros_bridge::ToRosTime(result.t_ns);
  // odom -> base stays continuous whatever happens; map -> odom, the pose in the map and the
  // path are published only for a pose that is a place in the map (not while lost or
  // searching: the ~health topic says which).
  tf_.sendTransform(Stamped(poses.T_odom_imu, stamp, frames_.odom, frames_.base));
  if (result.pose_status != odometry::PoseStatus::kValid) return;
  odometry_.publish(ToOdometryMsg(result, poses, frames_));
  tf_.sendTransform(Stamped(poses.T_world_odom, stamp, frames_.map, frames_.odom));
  geometry_msgs::PoseStamped pose;
  pose.header.stamp = stamp;
  pose.header.frame_id = frames_.map;
  pose.pose = ToPoseMsg(poses.T_world_imu);
  if (path_msg_.poses.size() >= options_.max_path_poses) {
    path_msg_.poses.erase(path_msg_.poses.begin());
  }
  path_msg_.poses.push_back(pose);
  path_msg_.header.stamp = stamp;
  if (path_.getNumSubscribers() > 0) path_.publish(path_msg_);
  if (!result.registered_points_map.empty() && scan_.getNumSubscribers() > 0) {
    scan_.publish(ToCloudMsg(result.registered_points_map, Eigen::Vector3d::Zero(), result.t_ns,
                             cloud_frame_));
  }
}

bool NodeOutputs::MapDue(int64_t t_ns, std::size_t map_size) const {
  if (!map_published_) return true;
  return t_ns - last_map_t_ns_ >= SecondsToNanos(options_.map_period_s) &&
         map_size != last_map_size_;
}

void NodeOutputs::PublishMap(const PointCloud& points_map, int64_t t_ns) {
  const PointCloud sampled =
      options_.map_voxel_m > 0.0
          ? registration::UniformSample(points_map, static_cast<float>(options_.map_voxel_m))
          : points_map;
  map_.publish(ToCloudMsg(sampled, Eigen::Vector3d::Zero(), t_ns, cloud_frame_));
  map_published_ = true;
  last_map_t_ns_ = t_ns;
  last_map_size_ = points_map.size();
}

void NodeOutputs::PublishHealth(const std::string& json) {
  std_msgs::String msg;
  msg.data = json;
  health_.publish(msg);
}

void NodeOutputs::PublishCostmap(const OccupancyGridData& grid) {
  costmap_.publish(ToGridMsg(grid, frames_.map, ros::Time::now()));
}

void NodeOutputs::PublishLidarExtrinsic(const std::string& lidar_frame,
                                        const Eigen::Isometry3d& T_imu_lidar) {
  static_tf_.sendTransform(Stamped(T_imu_lidar, ros::Time::now(), frames_.base, lidar_frame));
}

}  // namespace hylo::rosnode
