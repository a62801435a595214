#pragma once
// Everything the node publishes, in one place: odometry, TF (map → odom → base, and the static
// base → lidar extrinsic), the path, the registered scan, the latched map and costmap, health.
// Poses go out in the map frame in double. Clouds are float32 (as RViz and PCL read them),
// which at UTM-sized coordinates would round to decimetres: with a prior map's local origin
// they are published in `<map>_local` (a static child of map, translated by the origin) in
// the pipeline's local coordinates, and TF adds the origin back in double.

#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "frames.h"
#include "ros_messages.h"

namespace hylo::rosnode {

struct OutputOptions {
  double map_voxel_m = 0.5;        ///< voxel of the published (latched) map, m; 0 = every point
  double map_period_s = 5.0;       ///< republish the map at most this often (scan time), s
  std::size_t max_path_poses = 20000;  ///< the path keeps the newest poses only (flat memory)
  bool IsValid(std::string* why) const;
};

class NodeOutputs {
 public:
  NodeOutputs(ros::NodeHandle& nh, const FrameNames& frames, const OutputOptions& options);

  /// The prior map's local origin (world position of the pipeline's zero); before any output.
  /// A non-zero origin publishes the static map → <map>_local and moves the clouds there.
  void SetOrigin(const Eigen::Vector3d& origin_world);
  /// Odometry, TF map → odom → base, path and (if not empty) the registered scan.
  void PublishScan(const odometry::ScanResult& result);
  /// True when the map should be republished at scan time t_ns: never yet, or map_period_s
  /// passed and the map changed size (checked before the caller flattens the map).
  bool MapDue(int64_t t_ns, std::size_t map_size) const;
  /// The map (pipeline's map frame), downsampled; latched.
  void PublishMap(const PointCloud& points_map, int64_t t_ns);
  void PublishHealth(const std::string& json);
  void PublishCostmap(const OccupancyGridData& grid);
  /// Static base → `lidar_frame` from the configured extrinsic T_imu_lidar.
  void PublishLidarExtrinsic(const std::string& lidar_frame, const Eigen::Isometry3d& T_imu_lidar);

 private:
  FrameNames frames_;
  OutputOptions options_;
  Eigen::Vector3d origin_world_ = Eigen::Vector3d::Zero();
  std::string cloud_frame_;  ///< map, or <map>_local with a non-zero origin
  ros::Publisher odometry_, path_, scan_, map_, health_, costmap_;
  tf2_ros::TransformBroadcaster tf_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  nav_msgs::Path path_msg_;
  int64_t last_map_t_ns_ = 0;
  bool map_published_ = false;
  std::size_t last_map_size_ = 0;
};

}  // namespace hylo::rosnode
