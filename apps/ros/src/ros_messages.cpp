#include "ros_messages.h"

#include <algorithm>
#include <cstring>

#include "hylo/logs/ros_bridge.h"

namespace hylo::rosnode {

using logs::ros_bridge::FromRosTime;
using logs::ros_bridge::ToRosTime;

ImuSample FromRos(const sensor_msgs::Imu& msg, double accel_scale) {
  ImuSample sample;
  sample.t_ns = FromRosTime(msg.header.stamp);
  sample.accel_imu = accel_scale * Eigen::Vector3d(msg.linear_acceleration.x,
                                                   msg.linear_acceleration.y,
                                                   msg.linear_acceleration.z);
  sample.gyro_imu = {msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z};
  return sample;
}

Eigen::Isometry3d FromRos(const geometry_msgs::Pose& pose) {
  Eigen::Quaterniond q(pose.orientation.w, pose.orientation.x, pose.orientation.y,
                       pose.orientation.z);
  if (q.norm() < 1e-9) q = Eigen::Quaterniond::Identity();  // RViz sends unit quaternions
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return T;
}

geometry_msgs::Pose ToPoseMsg(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  geometry_msgs::Pose pose;
  pose.position.x = T.translation().x();
  pose.position.y = T.translation().y();
  pose.position.z = T.translation().z();
  pose.orientation.w = q.w();
  pose.orientation.x = q.x();
  pose.orientation.y = q.y();
  pose.orientation.z = q.z();
  return pose;
}

geometry_msgs::Transform ToTransformMsg(const Eigen::Isometry3d& T) {
  const geometry_msgs::Pose pose = ToPoseMsg(T);
  geometry_msgs::Transform transform;
  transform.translation.x = pose.position.x;
  transform.translation.y = pose.position.y;
  transform.translation.z = pose.position.z;
  transform.rotation = pose.orientation;
  return transform;
}

sensor_msgs::PointCloud2 ToCloudMsg(const PointCloud& points_map,
                                    const Eigen::Vector3d& origin_world, int64_t t_ns,
                                    const std::string& frame_id) {
  sensor_msgs::PointCloud2 msg;
  msg.header.stamp = ToRosTime(t_ns);
  msg.header.frame_id = frame_id;
  msg.height = 1;
  msg.width = static_cast<uint32_t>(points_map.size());
  const char* names[3] = {"x", "y", "z"};
  for (uint32_t i = 0; i < 3; ++i) {
    sensor_msgs::PointField field;
    field.name = names[i];
    field.offset = 4 * i;
    field.datatype = sensor_msgs::PointField::FLOAT32;
    field.count = 1;
    msg.fields.push_back(field);
  }
  msg.is_bigendian = false;
  msg.point_step = 12;
  msg.row_step = msg.point_step * msg.width;
  msg.is_dense = true;
  msg.data.resize(msg.row_step);
  uint8_t* out = msg.data.data();
  for (const Eigen::Vector3f& p : points_map) {
    // Add the origin in double, then round once: the local point keeps its precision.
    const float xyz[3] = {static_cast<float>(p.x() + origin_world.x()),
                          static_cast<float>(p.y() + origin_world.y()),
                          static_cast<float>(p.z() + origin_world.z())};
    std::memcpy(out, xyz, sizeof(xyz));
    out += sizeof(xyz);
  }
  return msg;
}

nav_msgs::OccupancyGrid ToGridMsg(const OccupancyGridData& grid, const std::string& frame_id,
                                  const ros::Time& stamp) {
  nav_msgs::OccupancyGrid msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame_id;
  msg.info.map_load_time = stamp;
  msg.info.resolution = static_cast<float>(grid.resolution_m);
  msg.info.width = static_cast<uint32_t>(grid.width);
  msg.info.height = static_cast<uint32_t>(grid.height);
  Eigen::Isometry3d T_world_grid = Eigen::Isometry3d::Identity();
  T_world_grid.translation() = Eigen::Vector3d(grid.origin_x_m, grid.origin_y_m, 0.0);
  T_world_grid.linear() =
      Eigen::AngleAxisd(grid.origin_yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  msg.info.origin = ToPoseMsg(T_world_grid);
  msg.data = grid.cells;
  return msg;
}

nav_msgs::Odometry ToOdometryMsg(const odometry::ScanResult& result, const FramePoses& poses,
                                 const FrameNames& frames) {
  nav_msgs::Odometry msg;
  msg.header.stamp = ToRosTime(result.t_ns);
  // Pose: in the map frame (the prior map file's; the origin is a pure translation, so the
  // map axes are the local frame's). Position block about the map axes as estimated; the
  // rotation block turned from the body axes (right perturbation) to the map axes.
  msg.header.frame_id = frames.map;
  msg.child_frame_id = frames.base;
  msg.pose.pose = ToPoseMsg(poses.T_world_imu);
  const std::array<double, 36> pose_cov = PoseCovarianceToRos(
      result.pose_covariance, Eigen::Matrix3d::Identity(), poses.T_world_imu.linear());
  std::copy(pose_cov.begin(), pose_cov.end(), msg.pose.covariance.begin());
  // Twist: in the child (base = IMU) frame, as ROS defines it and as the pipeline gives it.
  const Eigen::Vector3d& v = result.linear_velocity_imu;
  const Eigen::Vector3d& w = result.angular_velocity_imu;
  msg.twist.twist.linear.x = v.x();
  msg.twist.twist.linear.y = v.y();
  msg.twist.twist.linear.z = v.z();
  msg.twist.twist.angular.x = w.x();
  msg.twist.twist.angular.y = w.y();
  msg.twist.twist.angular.z = w.z();
  const std::array<double, 36> twist_cov = TwistCovarianceToRos(result.twist_covariance);
  std::copy(twist_cov.begin(), twist_cov.end(), msg.twist.covariance.begin());
  return msg;
}

}  // namespace hylo::rosnode
