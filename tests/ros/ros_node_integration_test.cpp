// End to end through ROS: a real roscore on loopback, a simulator bag played to ROS topics
// (bag_player.h), hylo_node, and this test as a ROS client (ros_graph.h). SLAM: the odometry's ATE
// after SE(3) alignment and the REP-105 tree map → odom → base_link. Localization: a prior map
// moved to UTM-like coordinates, the odometry compared with the truth *without* alignment
// (the published map frame is the file's), and a relocalization requested through the
// service mid-run. The inspection service's Path against `hylo inspect`'s route. Skipped,
// visibly, when roscore is missing.

#include <gtest/gtest.h>
#include <nav_msgs/GetPlan.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/SetMap.h>
#include <ros/topic.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Trigger.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "hylo/io/cloud_io.h"
#include "hylo/io/costmap_io.h"
#include "hylo/io/json.h"
#include "hylo/logs/ros_bridge.h"
#include "inspection_yard.h"
#include "ros_graph.h"
#include "ros_messages.h"
#include "test_data.h"

namespace hylo::rosnode {
namespace {

using hylo::testing::ChildProcess;
using hylo::testing::Tail;
using std::chrono::seconds;

const std::string kConfig = std::string(HYLO_SOURCE_DIR) + "/config/presets/sim_vlp16.yaml";
constexpr double kSlamAteBoundM = 0.15;            // `hylo map` reaches ~0.03 m offline on this bag
constexpr double kLocalizationErrorBoundM = 0.15;  // `hylo localize`: ~0.002 m offline

class RosNodeIntegration : public ::testing::Test {
 protected:
  void SetUp() override {
    if (hylo::testing::FindInPath("roscore").empty()) {
      GTEST_SKIP() << "roscore not in PATH (Debian: ros-core; scripts/setup.sh)";
    }
    // roscpp cannot be initialised twice in a process; ctest runs each case alone.
    static bool ros_used_in_this_process = false;
    if (ros_used_in_this_process) {
      GTEST_SKIP() << "one ROS graph per process: run each case alone (--gtest_filter; ctest does)";
    }
    ros_used_in_this_process = true;
    dir_ = hylo::testing::ScratchDir("ros_node");
  }
  void TearDown() override {
    graph_.reset();  // stops every process the test started
    // The bag is large: keep the folder (logs) only when the test failed.
    if (!dir_.empty() && !HasFailure()) std::filesystem::remove_all(dir_);
  }

  /// `hylo simulate` of session a into dir_/sim.
  void Simulate(int duration_s, bool site) {
    std::vector<std::string> argv = {std::string(HYLO_BINARY_DIR) + "/apps/hylo",
                                     "simulate",
                                     "--out",
                                     dir_ + "/sim",
                                     "--session",
                                     "a",
                                     "--duration",
                                     std::to_string(duration_s)};
    if (!site) argv.push_back("--no-site");
    ChildProcess simulate(argv, dir_ + "/simulate.log");
    const std::optional<int> code = simulate.Wait(seconds(60));
    ASSERT_TRUE(code && *code == 0) << Tail(dir_ + "/simulate.log");
  }

  std::string dir_;
  std::unique_ptr<hylo::testing::RosGraph> graph_ = std::make_unique<hylo::testing::RosGraph>();
};

void ExpectTfTreeAt(hylo::testing::Collected& c, const nav_msgs::Odometry& odom) {
  std::string error;
  ASSERT_TRUE(c.tf.canTransform("map", "odom", odom.header.stamp, &error)) << error;
  ASSERT_TRUE(c.tf.canTransform("odom", "base_link", odom.header.stamp, &error)) << error;
  const geometry_msgs::TransformStamped map_base =
      c.tf.lookupTransform("map", "base_link", odom.header.stamp);
  const Eigen::Vector3d p_tf(map_base.transform.translation.x, map_base.transform.translation.y,
                             map_base.transform.translation.z);
  EXPECT_LT((p_tf - FromRos(odom.pose.pose).translation()).norm(), 1e-6)
      << "map → odom → base_link must compose to the odometry pose";
}

TEST_F(RosNodeIntegration, SlamOdometryMatchesTruthAndTfTreeIsComplete) {
  ASSERT_NO_FATAL_FAILURE(Simulate(30, false));
  std::string error;
  ASSERT_TRUE(graph_->StartMaster(dir_, &error)) << error;
  ASSERT_TRUE(graph_->StartNode({"_config:=" + kConfig}, &error)) << error;
  ASSERT_TRUE(graph_->PlayBag(dir_ + "/sim/session_a.bag", &error)) << error;
  ASSERT_TRUE(graph_->NodeAlive()) << "hylo_node exited:\n" << graph_->NodeLog();

  // Late messages (stamped at the start of the bag) are counted on ~health, not fatal.
  hylo::testing::Collected& c = graph_->collected();
  ros::NodeHandle nh;
  ros::Publisher late_imu = nh.advertise<sensor_msgs::Imu>("/imu", 10);
  ASSERT_TRUE(
      hylo::testing::WaitFor([&] { return late_imu.getNumSubscribers() > 0; }, seconds(10)));
  for (int i = 0; i < 5; ++i) {
    sensor_msgs::Imu late;
    late.header.stamp.fromNSec(1'700'000'000'000'000'000ULL + 5'000'000ULL * i);
    late.linear_acceleration.z = 9.81;
    late_imu.publish(late);
  }
  EXPECT_TRUE(hylo::testing::WaitFor([&] { return c.HealthContains("\"imu_out_of_order\":5"); },
                                     seconds(5)));
  ASSERT_TRUE(graph_->NodeAlive()) << "hylo_node exited:\n" << graph_->NodeLog();

  std::lock_guard<std::mutex> lock(c.mutex);
  // 300 scans in the bag; the first second initialises the IMU at rest.
  ASSERT_GE(c.odometry.size(), 200u) << graph_->NodeLog();
  for (const nav_msgs::Odometry& odom : c.odometry) {
    ASSERT_EQ(odom.header.frame_id, "map");
    ASSERT_EQ(odom.child_frame_id, "base_link");
    for (int i = 0; i < 6; ++i) {
      ASSERT_GT(odom.pose.covariance[7 * i], 0.0) << "pose covariance diagonal " << i;
      ASSERT_TRUE(std::isfinite(odom.twist.covariance[7 * i])) << "twist covariance " << i;
    }
  }
  const evaluation::AteResult ate = evaluation::ComputeAte(
      hylo::testing::PosesOf(c.odometry),
      hylo::testing::ReadTruth(dir_ + "/sim/session_a_truth.tum", Eigen::Vector3d::Zero()));
  ASSERT_TRUE(ate.ok) << ate.message;
  std::printf(
      "[ros slam] %zu odometry messages, ATE (SE3-aligned) rmse %.4f m, max %.4f m, "
      "rot rmse %.3f deg, path %.1f m\n",
      c.odometry.size(), ate.rmse_m, ate.max_m, ate.rotation_rmse_deg, ate.path_length_m);
  EXPECT_EQ(ate.num_unmatched, 0u);
  EXPECT_LT(ate.rmse_m, kSlamAteBoundM);
  EXPECT_GT(ate.path_length_m, 20.0) << "the vehicle must move for the ATE to mean much";
  ExpectTfTreeAt(c, c.odometry.back());
  ASSERT_FALSE(c.health.empty());
  for (const std::string& h : c.health) {
    if (h.find("\"scans_dropped_full\":0") == std::string::npos) {
      std::printf("FIRST DROP: %s\n", h.c_str());
      break;
    }
  }
  EXPECT_NE(c.health.back().find("\"state\":\"localized\""), std::string::npos) << c.health.back();
  EXPECT_NE(c.health.back().find("\"mode\":\"slam\""), std::string::npos);
}

/// 16 numbers, row-major, as localization::ParsePoseGuess reads them.
std::string MatrixText(const Eigen::Isometry3d& T) {
  std::ostringstream os;
  os.precision(12);
  for (int r = 0; r < 4; ++r) {
    for (int col = 0; col < 4; ++col) os << T.matrix()(r, col) << ' ';
  }
  return os.str();
}

/// A 20 × 10 costmap at 0.5 m in the shifted frame, one lethal cell at (col 3, row 2).
void WriteCostmap(const std::string& yaml, const Eigen::Vector3d& offset) {
  terrain::GridGeometry g;
  g.origin_world = offset;
  g.resolution_m = 0.5;
  g.width = 20;
  g.height = 10;
  terrain::GridMap grid(g);
  grid.AddLayer(terrain::layers::kCost, 0.f)[g.Index(3, 2)] = 1.f;
  std::vector<terrain::CellClass> classes(g.NumCells(), terrain::CellClass::kFree);
  classes[g.Index(3, 2)] = terrain::CellClass::kLethal;
  io::WriteMapServer(yaml, grid, classes);
}

Eigen::Isometry3d Perturbed(Eigen::Isometry3d T, const Eigen::Vector3d& dp, double dyaw_rad) {
  T.translation() += dp;
  T.linear() = Eigen::AngleAxisd(dyaw_rad, Eigen::Vector3d::UnitZ()) * T.linear();
  return T;
}

TEST_F(RosNodeIntegration, LocalizesInAShiftedPriorMapAndRelocalizesOnRequest) {
  ASSERT_NO_FATAL_FAILURE(Simulate(20, true));
  // The prior map in UTM-like coordinates: the node must publish in the file's frame.
  const Eigen::Vector3d offset(500000.0, 4100000.0, 100.0);
  io::CloudFile map = io::ReadCloud(dir_ + "/sim/site_reference.pcd");
  for (Eigen::Vector3d& p : map.positions) p += offset;
  io::WriteCloud(dir_ + "/prior.pcd", map);
  const std::vector<evaluation::TimedPose> truth =
      hylo::testing::ReadTruth(dir_ + "/sim/session_a_truth.tum", offset);
  const Eigen::Isometry3d guess =
      Perturbed(truth.front().T_world_body, Eigen::Vector3d(0.4, -0.3, 0.0), 4.0 * M_PI / 180);

  std::string error;
  ASSERT_TRUE(graph_->StartMaster(dir_, &error)) << error;
  WriteCostmap(dir_ + "/costmap.yaml", offset);
  ASSERT_TRUE(graph_->StartNode(
      {"_config:=" + kConfig, "_prior_map:=" + dir_ + "/prior.pcd",
       "_initial_guess:=" + MatrixText(guess), "_costmap:=" + dir_ + "/costmap.yaml",
       "_save_map_path:=" + dir_ + "/saved_map.pcd"},
      &error))
      << error;
  // The costmap is latched: a late subscriber gets it.
  ros::NodeHandle nh;
  const auto grid = ros::topic::waitForMessage<nav_msgs::OccupancyGrid>("/hylo_node/costmap", nh,
                                                                        ros::Duration(10.0));
  ASSERT_NE(grid, nullptr) << "no latched ~costmap";
  EXPECT_EQ(grid->header.frame_id, "map");
  ASSERT_EQ(grid->info.width, 20u);
  ASSERT_EQ(grid->info.height, 10u);
  EXPECT_NEAR(grid->info.origin.position.x, offset.x(), 1e-6);
  EXPECT_EQ(grid->data[2 * 20 + 3], 100);
  EXPECT_EQ(grid->data[0], 0);
  // Clouds are float32: published in map_local (the prior's local origin), placed by TF.
  const auto prior_cloud = ros::topic::waitForMessage<sensor_msgs::PointCloud2>(
      "/hylo_node/map_cloud", nh, ros::Duration(10.0));
  ASSERT_NE(prior_cloud, nullptr) << "no latched ~map_cloud";
  EXPECT_EQ(prior_cloud->header.frame_id, "map_local");
  EXPECT_GT(prior_cloud->width, 1000u);
  hylo::testing::Collected& c = graph_->collected();
  graph_->StartBag(dir_ + "/sim/session_a.bag");
  // Mid-run, relocalize through the service from a rough pose near the truth.
  ASSERT_TRUE(hylo::testing::WaitFor([&] { return c.NumOdometry() >= 80; }, seconds(40)))
      << graph_->NodeLog();
  Eigen::Isometry3d now;
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    const int64_t t_ns = logs::ros_bridge::FromRosTime(c.odometry.back().header.stamp);
    ASSERT_TRUE(evaluation::InterpolatePose(truth, t_ns, &now));
  }
  nav_msgs::SetMap relocalize;
  relocalize.request.initial_pose.header.frame_id = "map";
  relocalize.request.initial_pose.pose.pose =
      ToPoseMsg(Perturbed(now, Eigen::Vector3d(0.3, 0.2, 0.0), -3.0 * M_PI / 180));
  ASSERT_TRUE(ros::service::call("/hylo_node/relocalize", relocalize));
  EXPECT_TRUE(relocalize.response.success);
  ASSERT_TRUE(graph_->WaitForPlayer(&error)) << error;
  ASSERT_TRUE(graph_->NodeAlive()) << "hylo_node exited:\n" << graph_->NodeLog();
  std_srvs::Trigger save;
  ASSERT_TRUE(ros::service::call("/hylo_node/save_map", save));
  ASSERT_TRUE(save.response.success) << save.response.message;
  const io::CloudFile saved = io::ReadCloud(dir_ + "/saved_map.pcd");
  ASSERT_GT(saved.positions.size(), 1000u);
  EXPECT_LT((saved.positions.front() - offset).norm(), 200.0) << "saved in the file's frame";

  std::lock_guard<std::mutex> lock(c.mutex);
  ASSERT_GE(c.odometry.size(), 140u) << graph_->NodeLog();
  evaluation::AteOptions absolute;
  absolute.alignment = evaluation::Alignment::kNone;
  const evaluation::AteResult ate =
      evaluation::ComputeAte(hylo::testing::PosesOf(c.odometry), truth, absolute);
  ASSERT_TRUE(ate.ok) << ate.message;
  std::printf(
      "[ros localization] %zu odometry messages, error in the map frame (no alignment) "
      "rmse %.4f m, max %.4f m, rot rmse %.3f deg\n",
      c.odometry.size(), ate.rmse_m, ate.max_m, ate.rotation_rmse_deg);
  EXPECT_LT(ate.rmse_m, kLocalizationErrorBoundM);
  EXPECT_LT(ate.max_m, 2 * kLocalizationErrorBoundM);
  ExpectTfTreeAt(c, c.odometry.back());
  ASSERT_TRUE(c.tf.canTransform("map", "map_local", ros::Time(0), &error)) << error;
  const geometry_msgs::TransformStamped map_local =
      c.tf.lookupTransform("map", "map_local", ros::Time(0));
  const Eigen::Vector3d origin(map_local.transform.translation.x, map_local.transform.translation.y,
                               map_local.transform.translation.z);
  EXPECT_LT((origin - offset).norm(), 200.0) << "the local origin lies in the shifted site";
  bool relocalized = false, localization_mode = false;
  for (const std::string& h : c.health) {
    relocalized |= h.find("\"last_event\":\"relocalized") != std::string::npos;
    localization_mode |= h.find("\"mode\":\"localization\"") != std::string::npos;
  }
  EXPECT_TRUE(relocalized) << "no relocalized event on ~health; last: " << c.health.back();
  EXPECT_TRUE(localization_mode);
  EXPECT_NE(c.health.back().find("\"state\":\"localized\""), std::string::npos) << c.health.back();
}

// No ~initial_guess: the node starts by searching the whole prior map; mid-run, ~global_localize
// makes it forget its pose and search again while the vehicle drives. No odometry may be
// published at a wrong place at any time (compared with the truth without alignment).
TEST_F(RosNodeIntegration, StartsGloballyAndSearchesAgainOnRequest) {
  ASSERT_NO_FATAL_FAILURE(Simulate(20, true));
  const std::vector<evaluation::TimedPose> truth =
      hylo::testing::ReadTruth(dir_ + "/sim/session_a_truth.tum", Eigen::Vector3d::Zero());
  std::string error;
  ASSERT_TRUE(graph_->StartMaster(dir_, &error)) << error;
  ASSERT_TRUE(graph_->StartNode(
      {"_config:=" + kConfig, "_prior_map:=" + dir_ + "/sim/site_reference.pcd"}, &error))
      << error;
  hylo::testing::Collected& c = graph_->collected();
  graph_->StartBag(dir_ + "/sim/session_a.bag");
  ASSERT_TRUE(hylo::testing::WaitFor([&] { return c.NumOdometry() >= 50; }, seconds(40)))
      << graph_->NodeLog();
  std::size_t before_request = 0;
  std::size_t dropped_before_request = 0;
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    before_request = c.odometry.size();
    ASSERT_FALSE(c.health.empty());
    dropped_before_request = io::Json::parse(c.health.back())
                                 .at("input")
                                 .at("scans_dropped_full")
                                 .get<std::size_t>();
  }
  std_srvs::Trigger global;
  ASSERT_TRUE(ros::service::call("/hylo_node/global_localize", global));
  EXPECT_TRUE(global.response.success) << global.response.message;
  ASSERT_TRUE(graph_->WaitForPlayer(&error)) << error;
  ASSERT_TRUE(graph_->NodeAlive()) << "hylo_node exited:\n" << graph_->NodeLog();

  EXPECT_TRUE(c.HealthContains("\"last_event\":\"initialized: global localization accepted"))
      << graph_->NodeLog();
  EXPECT_TRUE(c.HealthContains("\"last_event\":\"searching: global localization requested"))
      << graph_->NodeLog();
  EXPECT_TRUE(c.HealthContains("\"last_event\":\"relocalized: global localization accepted"))
      << graph_->NodeLog();
  std::lock_guard<std::mutex> lock(c.mutex);
  EXPECT_GT(c.odometry.size(), before_request + 20) << "odometry must resume after the search";
  // The searches, the start's and the requested one, ran beside the scan path, not in its
  // way: no scan waited long enough in the node's queue to be dropped.
  ASSERT_FALSE(c.health.empty());
  const io::Json input = io::Json::parse(c.health.back()).at("input");
  EXPECT_EQ(dropped_before_request, 0u) << "dropped while the start searched";
  EXPECT_EQ(input.at("scans_dropped_full").get<std::size_t>(), 0u) << c.health.back();
  EXPECT_GT(input.at("scans_received").get<std::size_t>(), before_request + 20);
  evaluation::AteOptions absolute;
  absolute.alignment = evaluation::Alignment::kNone;
  const evaluation::AteResult ate =
      evaluation::ComputeAte(hylo::testing::PosesOf(c.odometry), truth, absolute);
  ASSERT_TRUE(ate.ok) << ate.message;
  std::printf(
      "[ros global] %zu odometry messages (%zu before the request), error in the map "
      "frame rmse %.4f m, max %.4f m\n",
      c.odometry.size(), before_request, ate.rmse_m, ate.max_m);
  EXPECT_LT(ate.max_m, 2 * kLocalizationErrorBoundM);
}

/// route.csv's x, y columns.
std::vector<Eigen::Vector2d> ReadRouteCsv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<Eigen::Vector2d> route;
  while (std::getline(in, line)) {
    Eigen::Vector2d xy;
    if (std::sscanf(line.c_str(), "%lf,%lf", &xy.x(), &xy.y()) == 2) route.push_back(xy);
  }
  return route;
}

// ~plan_inspection through ROS: the nav_msgs/Path a GetPlan call returns is `hylo inspect`'s
// route.csv for the same files and start, in the map frame; a start in another frame, or an
// empty frame (the current pose) before the node has a pose, is refused.
TEST_F(RosNodeIntegration, PlanInspectionReturnsTheCommandsRouteAsPath) {
  const Eigen::Vector3d offset(1000.0, 2000.0, 50.0);
  const hylo::testing::InspectionYard yard =
      hylo::testing::WriteInspectionYard(dir_ + "/yard", offset);
  ChildProcess inspect(
      {std::string(HYLO_BINARY_DIR) + "/apps/hylo", "inspect", "--map", yard.map, "--costmap",
       yard.costmap_dir, "--targets", yard.targets, "--start", "1002 2002", "--out", dir_ + "/cli"},
      dir_ + "/inspect.log");
  const std::optional<int> code = inspect.Wait(seconds(60));
  ASSERT_TRUE(code && *code == 0) << Tail(dir_ + "/inspect.log");
  const std::vector<Eigen::Vector2d> cli_route = ReadRouteCsv(dir_ + "/cli/route.csv");
  ASSERT_GE(cli_route.size(), 4u);

  std::string error;
  ASSERT_TRUE(graph_->StartMaster(dir_, &error)) << error;
  ASSERT_TRUE(graph_->StartNode(
      {"_config:=" + kConfig, "_inspection_map:=" + yard.map,
       "_inspection_costmap:=" + yard.costmap_dir, "_inspection_targets:=" + yard.targets},
      &error))
      << error;
  ASSERT_TRUE(ros::service::waitForService("/hylo_node/plan_inspection", ros::Duration(20.0)))
      << graph_->NodeLog();
  nav_msgs::GetPlan plan;
  plan.request.start.header.frame_id = "map";
  plan.request.start.pose.position.x = 1002.0;
  plan.request.start.pose.position.y = 2002.0;
  ASSERT_TRUE(ros::service::call("/hylo_node/plan_inspection", plan)) << graph_->NodeLog();
  EXPECT_EQ(plan.response.plan.header.frame_id, "map");
  ASSERT_EQ(plan.response.plan.poses.size(), cli_route.size());
  for (std::size_t i = 0; i < cli_route.size(); ++i) {
    const geometry_msgs::Point& p = plan.response.plan.poses[i].pose.position;
    EXPECT_NEAR(p.x, cli_route[i].x(), 1e-3) << i;  // route.csv has millimetres
    EXPECT_NEAR(p.y, cli_route[i].y(), 1e-3) << i;
  }
  nav_msgs::GetPlan other_frame = plan;
  other_frame.request.start.header.frame_id = "odom";
  EXPECT_FALSE(ros::service::call("/hylo_node/plan_inspection", other_frame));
  nav_msgs::GetPlan current_pose;  // empty frame_id: no bag played, so no pose yet
  EXPECT_FALSE(ros::service::call("/hylo_node/plan_inspection", current_pose));
  EXPECT_TRUE(graph_->NodeAlive()) << graph_->NodeLog();
  EXPECT_NE(graph_->NodeLog().find("no valid pose yet"), std::string::npos) << graph_->NodeLog();
}

}  // namespace
}  // namespace hylo::rosnode
