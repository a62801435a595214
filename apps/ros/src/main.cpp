// hylo_node: lidar-inertial odometry and localization for a ROS1 navigation stack.
// `rosrun`/roslaunch with ~config (run configuration YAML) and optionally ~prior_map +
// ~initial_guess (localization), ~costmap (map_server YAML); see hylo_node.h and README.

#include <ros/ros.h>

#include <exception>

#include "hylo_node.h"
#include "node_params.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "hylo_node");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  try {
    const hylo::rosnode::NodeParams params = hylo::rosnode::ReadNodeParams(private_nh);
    hylo::rosnode::HyloNode node(nh, private_nh, params);
    // Callbacks (decoding, services) on two threads; the pipeline runs on this one.
    ros::AsyncSpinner spinner(2);
    spinner.start();
    node.Run();
    spinner.stop();
  } catch (const std::exception& e) {
    ROS_FATAL("hylo_node: %s", e.what());
    return 1;
  }
  return 0;
}
