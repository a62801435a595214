#pragma once
// A private ROS graph for one integration test process: roscore on a free loopback port
// (ROS_MASTER_URI / ROS_HOSTNAME / ROS_HOME set for every child), hylo_node, a bag player
// (bag_player.h), and this process as a ROS client collecting the node's odometry, /tf and
// health. The player, the node and the master are stopped by the destructor, in that order,
// on every exit path.
// ros::init runs once per process: one RosGraph per test process (ctest runs each case alone).

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <tf2/buffer_core.h>
#include <tf2_msgs/TFMessage.h>

#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "bag_player.h"
#include "child_process.h"
#include "hylo/evaluation/trajectory_metrics.h"

namespace hylo::testing {

/// What the test hears from the node (callbacks on a spinner thread; lock `mutex` to read).
struct Collected {
  std::mutex mutex;
  std::vector<nav_msgs::Odometry> odometry;
  tf2::BufferCore tf{ros::Duration(120.0)};
  std::vector<std::string> health;

  void OnOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void OnTf(const tf2_msgs::TFMessage::ConstPtr& msg);
  void OnTfStatic(const tf2_msgs::TFMessage::ConstPtr& msg);
  void OnHealth(const std_msgs::String::ConstPtr& msg);
  std::size_t NumOdometry();
  /// True when some health message contains `text`.
  bool HealthContains(const std::string& text);
};

class RosGraph {
 public:
  /// Starts roscore in `dir` (logs and ROS_HOME there); false with the log on failure.
  bool StartMaster(const std::string& dir, std::string* error);
  /// Starts hylo_node with `params` ("_name:=value") and subscribes to its outputs; false
  /// with the node's log when it exits or does not advertise within 20 s.
  bool StartNode(const std::vector<std::string>& params, std::string* error);
  /// Plays `bag` to the end (once the node subscribed), then waits until the node's odometry
  /// stops growing. False with why on failure.
  bool PlayBag(const std::string& bag, std::string* error);
  /// Starts the bag without waiting (see WaitForPlayer).
  void StartBag(const std::string& bag);
  bool WaitForPlayer(std::string* error);
  /// True while the node runs.
  bool NodeAlive();
  std::string NodeLog() const;

  Collected& collected() { return collected_; }
  ~RosGraph();

 private:
  std::string dir_;
  std::unique_ptr<ChildProcess> roscore_, node_;
  std::unique_ptr<BagPlayer> player_;
  std::unique_ptr<ros::NodeHandle> nh_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
  std::vector<ros::Subscriber> subscribers_;
  Collected collected_;
};

/// The odometry as timed poses (map frame → base), for trajectory_metrics.
std::vector<evaluation::TimedPose> PosesOf(const std::vector<nav_msgs::Odometry>& odometry);
/// A TUM file as timed poses, each moved by `offset_world` (m).
std::vector<evaluation::TimedPose> ReadTruth(const std::string& path,
                                             const Eigen::Vector3d& offset_world);

/// Polls `done` every 50 ms until true or `timeout`; false on timeout.
template <typename Predicate>
bool WaitFor(Predicate done, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return true;
}

}  // namespace hylo::testing
