#include "ros_graph.h"

#include <cstdlib>
#include <thread>

#include "hylo/logs/ros_bridge.h"
#include "hylo/io/trajectory_io.h"
#include "ros_messages.h"

namespace hylo::testing {

using std::chrono::milliseconds;
using std::chrono::seconds;

void Collected::OnOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex);
  odometry.push_back(*msg);
}

void Collected::OnTf(const tf2_msgs::TFMessage::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto& t : msg->transforms) tf.setTransform(t, "hylo_node");
}

void Collected::OnTfStatic(const tf2_msgs::TFMessage::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto& t : msg->transforms) tf.setTransform(t, "hylo_node", /*is_static=*/true);
}

void Collected::OnHealth(const std_msgs::String::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex);
  health.push_back(msg->data);
}

std::size_t Collected::NumOdometry() {
  std::lock_guard<std::mutex> lock(mutex);
  return odometry.size();
}

bool Collected::HealthContains(const std::string& text) {
  std::lock_guard<std::mutex> lock(mutex);
  for (const std::string& h : health) {
    if (h.find(text) != std::string::npos) return true;
  }
  return false;
}

bool RosGraph::StartMaster(const std::string& dir, std::string* error) {
  dir_ = dir;
  const int port = FreeLoopbackPort();
  // Inherited by every child: the test's own master, on loopback, logs in the scratch dir.
  ::setenv("ROS_MASTER_URI", ("http://127.0.0.1:" + std::to_string(port)).c_str(), 1);
  ::setenv("ROS_HOSTNAME", "127.0.0.1", 1);
  ::setenv("ROS_HOME", (dir_ + "/ros_home").c_str(), 1);
  ::unsetenv("ROS_IP");
  roscore_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{"roscore", "-p", std::to_string(port)}, dir_ + "/roscore.log");
  int argc = 0;
  ros::init(argc, nullptr, "hylo_integration_test",
            ros::init_options::NoSigintHandler | ros::init_options::AnonymousName);
  if (!WaitFor([] { return ros::master::check(); }, seconds(20))) {
    *error = "roscore did not come up:\n" + Tail(roscore_->log_path());
    return false;
  }
  nh_ = std::make_unique<ros::NodeHandle>();
  spinner_ = std::make_unique<ros::AsyncSpinner>(1);
  spinner_->start();
  return true;
}

bool RosGraph::StartNode(const std::vector<std::string>& params, std::string* error) {
  std::vector<std::string> argv = {std::string(HYLO_BINARY_DIR) + "/apps/ros/hylo_node",
                                   "__name:=hylo_node"};
  argv.insert(argv.end(), params.begin(), params.end());
  node_ = std::make_unique<ChildProcess>(argv, dir_ + "/node.log");
  subscribers_.push_back(
      nh_->subscribe("/hylo_node/odometry", 1000, &Collected::OnOdometry, &collected_));
  subscribers_.push_back(nh_->subscribe("/tf", 1000, &Collected::OnTf, &collected_));
  subscribers_.push_back(nh_->subscribe("/tf_static", 10, &Collected::OnTfStatic, &collected_));
  subscribers_.push_back(
      nh_->subscribe("/hylo_node/health", 1000, &Collected::OnHealth, &collected_));
  const ros::Subscriber& odometry = subscribers_.front();
  WaitFor([&] { return odometry.getNumPublishers() > 0 || node_->Poll(); }, seconds(20));
  if (odometry.getNumPublishers() == 0 || node_->Poll()) {
    *error = "hylo_node did not start:\n" + NodeLog();
    return false;
  }
  return true;
}

void RosGraph::StartBag(const std::string& bag) {
  player_ = std::make_unique<BagPlayer>(*nh_, bag, seconds(20));
}

bool RosGraph::WaitForPlayer(std::string* error) {
  if (!player_->Wait(seconds(90), error)) return false;
  // The node may still be working through its queue: wait until the odometry stops growing.
  std::size_t count = 0;
  WaitFor([&] {
    std::this_thread::sleep_for(milliseconds(400));
    const std::size_t now = collected_.NumOdometry();
    const bool settled = now == count && now > 0;
    count = now;
    return settled;
  }, seconds(10));
  return true;
}

bool RosGraph::PlayBag(const std::string& bag, std::string* error) {
  StartBag(bag);
  return WaitForPlayer(error);
}

bool RosGraph::NodeAlive() { return node_ && !node_->Poll(); }

std::string RosGraph::NodeLog() const { return node_ ? Tail(node_->log_path()) : ""; }

RosGraph::~RosGraph() {
  // Children first (player, node), then this client, then the master they talk to.
  player_.reset();
  node_.reset();
  if (spinner_) spinner_->stop();
  subscribers_.clear();
  nh_.reset();
  if (ros::isStarted()) ros::shutdown();
  roscore_.reset();
}

std::vector<evaluation::TimedPose> PosesOf(const std::vector<nav_msgs::Odometry>& odometry) {
  std::vector<evaluation::TimedPose> poses;
  for (const nav_msgs::Odometry& odom : odometry) {
    evaluation::TimedPose pose;
    pose.t_ns = logs::ros_bridge::FromRosTime(odom.header.stamp);
    pose.T_world_body = rosnode::FromRos(odom.pose.pose);
    poses.push_back(pose);
  }
  return poses;
}

std::vector<evaluation::TimedPose> ReadTruth(const std::string& path,
                                             const Eigen::Vector3d& offset_world) {
  std::vector<evaluation::TimedPose> truth;
  for (const io::StampedPose& p : io::ReadTum(path)) {
    evaluation::TimedPose pose{p.t_ns, p.T_world_body()};
    pose.T_world_body.translation() += offset_world;
    truth.push_back(pose);
  }
  return truth;
}

}  // namespace hylo::testing
