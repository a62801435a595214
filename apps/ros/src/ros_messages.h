#pragma once
// The node's ROS messages: ImuSample and poses on the way in (clouds and stamps go through
// io's ros_bridge.h, as for bags); scan results → nav_msgs/geometry_msgs/sensor_msgs on the
// way out.

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "costmap_grid.h"
#include "frames.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/logs/pointcloud2.h"

namespace hylo::rosnode {

/// Frame names of the outputs (output.map_frame / odom_frame / base_frame of the YAML).
struct FrameNames {
  std::string map = "map";
  std::string odom = "odom";
  std::string base = "base_link";
};

/// The sample in the IMU frame, accelerations multiplied by `accel_scale` (drivers in g).
ImuSample FromRos(const sensor_msgs::Imu& msg, double accel_scale);

Eigen::Isometry3d FromRos(const geometry_msgs::Pose& pose);
geometry_msgs::Pose ToPoseMsg(const Eigen::Isometry3d& T);
geometry_msgs::Transform ToTransformMsg(const Eigen::Isometry3d& T);

/// x y z float32 cloud in `frame_id`, `origin_world` added to every point (in double, then
/// rounded once). float32, as RViz and PCL expect: keep the coordinates small (node_outputs.h
/// publishes in the local frame).
sensor_msgs::PointCloud2 ToCloudMsg(const PointCloud& points_map,
                                    const Eigen::Vector3d& origin_world, int64_t t_ns,
                                    const std::string& frame_id);

/// The costmap as an OccupancyGrid in `frame_id`.
nav_msgs::OccupancyGrid ToGridMsg(const OccupancyGridData& grid, const std::string& frame_id,
                                  const ros::Time& stamp);

/// Pose (map frame → base, with its covariance about the map axes) and body twist (base
/// frame) of one scan result, stamped at the scan end.
nav_msgs::Odometry ToOdometryMsg(const odometry::ScanResult& result, const FramePoses& poses,
                                 const FrameNames& frames);

}  // namespace hylo::rosnode
