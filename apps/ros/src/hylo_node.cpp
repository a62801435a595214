#include "hylo_node.h"

#include <chrono>
#include <stdexcept>

#include "hylo/lie/isometry.h"
#include "hylo/localization/pose_guess.h"
#include "hylo/logs/ros_bridge.h"
#include "hylo/run/prior_map_io.h"
#include "ros_messages.h"

namespace hylo::rosnode {
namespace {

using Status = odometry::OdometryPipeline::Status;
using EventKind = localization::LocalizationEvent::Kind;

FrameNames FramesOf(const config::RunConfig& config) {
  return {config.output.map_frame, config.output.odom_frame, config.output.base_frame};
}

odometry::OdometryPipelineOptions PipelineOptionsFor(const config::RunConfig& config,
                                                       const NodeParams& params) {
  odometry::OdometryPipelineOptions options = config.PipelineOptions();
  // Live: a search's global attempts run beside the scan path, which never waits for them.
  options.localization.search.background = true;
  if (params.registered_scan_voxel_m >= 0.0) {
    options.output.dense_map_voxel_m = params.registered_scan_voxel_m;
  }
  return options;
}

InputQueueOptions QueueOptionsFor(const config::RunConfig& config, const NodeParams& params) {
  InputQueueOptions options = params.queue;
  options.wait_for_imu = config.pipeline.imu.enabled;
  return options;
}

}  // namespace

HyloNode::HyloNode(ros::NodeHandle nh, ros::NodeHandle private_nh, const NodeParams& params)
    : nh_(nh),
      private_nh_(private_nh),
      params_(params),
      config_(config::LoadRunConfig(params.config_path)),
      frames_(FramesOf(config_)),
      // A live node keeps no results and no dense map: its memory stays flat.
      session_(PipelineOptionsFor(config_, params), run::SessionKeeps{false, false}),
      pipeline_(session_.pipeline()),
      input_(QueueOptionsFor(config_, params)),
      outputs_(private_nh_, frames_, params.outputs),
      convention_(config_.lidar.time_convention) {
  if (!params_.prior_map.empty()) LoadPriorMap();
  if (!params_.costmap.empty()) outputs_.PublishCostmap(ReadMapServerMap(params_.costmap));
  // roscpp's queues only buffer between the socket and the callbacks, which decode and
  // enqueue; the bounded InputQueue is where messages wait for the worker.
  cloud_sub_ = nh_.subscribe(config_.lidar.topic, 20, &HyloNode::OnCloud, this);
  if (config_.pipeline.imu.enabled) {
    imu_sub_ = nh_.subscribe(config_.imu.topic, 2000, &HyloNode::OnImu, this,
                             ros::TransportHints().tcpNoDelay());
  }
  initial_pose_sub_ = nh_.subscribe("/initialpose", 2, &HyloNode::OnInitialPose, this);
  relocalize_srv_ = private_nh_.advertiseService("relocalize", &HyloNode::OnRelocalize, this);
  global_localize_srv_ =
      private_nh_.advertiseService("global_localize", &HyloNode::OnGlobalLocalize, this);
  save_map_srv_ = private_nh_.advertiseService("save_map", &HyloNode::OnSaveMap, this);
  if (!params_.inspection_targets.empty()) {
    inspection_ = std::make_unique<const InspectionService>(
        params_.inspection_map, params_.inspection_costmap, params_.inspection_targets,
        config_.inspection);
    plan_inspection_srv_ =
        private_nh_.advertiseService("plan_inspection", &HyloNode::OnPlanInspection, this);
    ROS_INFO("hylo_node: ~plan_inspection for %zu targets of %s", inspection_->num_targets(),
             params_.inspection_targets.c_str());
  }
  ROS_INFO("hylo_node: %s, back-end %s, lidar %s, imu %s, frames %s -> %s -> %s",
           session_.localizing() ? "localization in a prior map" : "SLAM", config_.BackendName().c_str(),
           config_.lidar.topic.c_str(),
           config_.pipeline.imu.enabled ? config_.imu.topic.c_str() : "none", frames_.map.c_str(),
           frames_.odom.c_str(), frames_.base.c_str());
}

void HyloNode::LoadPriorMap() {
  const std::string guess =
      params_.initial_guess.empty() ? config_.initial_guess : params_.initial_guess;
  if (guess.empty() && !config_.pipeline.localization.global_enabled) {
    throw std::runtime_error(
        "~prior_map without ~initial_guess (\"x y z roll pitch yaw\", m "
        "and deg) needs localization.global_enabled in " +
        params_.config_path);
  }
  std::optional<Eigen::Isometry3d> T_world_imu;  // none: the whole map is searched
  try {
    if (!guess.empty()) T_world_imu = localization::ParsePoseGuess(guess);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("initial guess: ") + e.what());
  }
  session_.LoadPriorMap(params_.prior_map, config_.prior_map, T_world_imu);
  const mapping::PriorMap& prior = session_.prior();
  outputs_.SetOrigin(session_.origin_world());
  outputs_.PublishMap(prior.points_local, 0);
  ROS_INFO("hylo_node: prior map %s, %zu points kept of %zu, origin (%.1f, %.1f, %.1f)",
           params_.prior_map.c_str(), prior.num_kept, prior.num_input, prior.origin_world.x(),
           prior.origin_world.y(), prior.origin_world.z());
}

void HyloNode::OnCloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
  logs::PointCloud2Message cloud = logs::ros_bridge::FromRos(*msg);
  if (convention_ == logs::PointTimeConvention::kAuto) {
    convention_ = logs::DetectPointTimeConvention(cloud.fields);
  }
  LidarScan scan;
  try {
    scan = logs::DecodePointCloud2(cloud, convention_, nullptr);
  } catch (const std::runtime_error& e) {
    ++undecodable_scans_;
    ROS_WARN_THROTTLE(5.0, "hylo_node: %s: scan skipped (%zu so far): %s",
                      config_.lidar.topic.c_str(), undecodable_scans_, e.what());
    return;
  }
  // The extrinsic as a static TF, unless the driver already stamps clouds in the base frame.
  if (!lidar_extrinsic_published_ && !msg->header.frame_id.empty() &&
      msg->header.frame_id != frames_.base) {
    outputs_.PublishLidarExtrinsic(msg->header.frame_id, config_.T_imu_lidar.ToIsometry());
    lidar_extrinsic_published_ = true;
  }
  if (!input_.PushScan(std::move(scan))) {
    ROS_WARN_THROTTLE(5.0, "hylo_node: late or out-of-order scan dropped (see ~health)");
  }
}

void HyloNode::OnImu(const sensor_msgs::Imu::ConstPtr& msg) {
  const ImuSample sample = FromRos(*msg, config_.imu.accel_scale);
  if (!sample.accel_imu.allFinite() || !sample.gyro_imu.allFinite()) return;
  if (!input_.PushImu(sample)) {
    ROS_WARN_THROTTLE(5.0, "hylo_node: late or out-of-order IMU sample dropped (see ~health)");
  }
}

bool HyloNode::RequestRelocalization(const std::string& frame_id,
                                     const Eigen::Isometry3d& T_world_imu, std::string* why) {
  if (!session_.localizing()) {
    *why = "no prior map (SLAM mode): nothing to relocalize against";
    return false;
  }
  if (!frame_id.empty() && frame_id != frames_.map) {
    *why = "pose in frame '" + frame_id + "', expected '" + frames_.map + "'";
    return false;
  }
  {
    std::lock_guard<std::mutex> lock(request_mutex_);
    relocalization_request_ = mapping::PoseToLocal(T_world_imu, session_.origin_world());
  }
  input_.Notify();
  return true;
}

void HyloNode::OnInitialPose(const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& msg) {
  std::string why;
  if (!RequestRelocalization(msg->header.frame_id, FromRos(msg->pose.pose), &why)) {
    ROS_WARN("hylo_node: /initialpose ignored: %s", why.c_str());
  }
}

bool HyloNode::OnRelocalize(nav_msgs::SetMap::Request& request,
                            nav_msgs::SetMap::Response& response) {
  std::string why;
  response.success = RequestRelocalization(request.initial_pose.header.frame_id,
                                           FromRos(request.initial_pose.pose.pose), &why);
  if (!response.success) ROS_WARN("hylo_node: ~relocalize refused: %s", why.c_str());
  return true;
}

void HyloNode::AskWorker(std::vector<std::shared_ptr<std::promise<std::string>>>* queue,
                         std_srvs::Trigger::Response* response) {
  auto promise = std::make_shared<std::promise<std::string>>();
  std::future<std::string> answer = promise->get_future();
  {
    std::lock_guard<std::mutex> lock(request_mutex_);
    queue->push_back(promise);
  }
  input_.Notify();
  if (answer.wait_for(std::chrono::seconds(60)) != std::future_status::ready) {
    response->success = false;
    response->message = "the worker did not answer within 60 s";
    return;
  }
  try {
    response->message = answer.get();
    response->success = true;
  } catch (const std::exception& e) {
    response->success = false;
    response->message = e.what();
  }
}

bool HyloNode::OnGlobalLocalize(std_srvs::Trigger::Request&,
                                std_srvs::Trigger::Response& response) {
  AskWorker(&global_requests_, &response);
  if (!response.success)
    ROS_WARN("hylo_node: ~global_localize refused: %s", response.message.c_str());
  return true;
}

bool HyloNode::OnSaveMap(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  AskWorker(&save_requests_, &response);
  return true;
}

bool HyloNode::OnPlanInspection(nav_msgs::GetPlan::Request& request,
                                nav_msgs::GetPlan::Response& response) {
  std::optional<Eigen::Isometry3d> pose;
  {
    std::lock_guard<std::mutex> lock(request_mutex_);
    pose = last_valid_T_world_imu_;
  }
  const geometry_msgs::PoseStamped& start = request.start;
  std::string why;
  const std::optional<Eigen::Vector2d> start_map =
      ResolveStart(start.header.frame_id, {start.pose.position.x, start.pose.position.y}, pose,
                   frames_.map, &why);
  std::vector<Eigen::Vector2d> route;
  if (!start_map || !inspection_->Plan(*start_map, &route, &why)) {
    ROS_WARN("hylo_node: ~plan_inspection refused: %s", why.c_str());
    return false;
  }
  ROS_INFO("hylo_node: ~plan_inspection from (%.2f, %.2f): %s", start_map->x(), start_map->y(),
           why.c_str());
  response.plan = ToPathMsg(route, frames_.map, ros::Time::now());
  return true;
}

void HyloNode::ServeRequests() {
  std::optional<Eigen::Isometry3d> relocalization;
  std::vector<std::shared_ptr<std::promise<std::string>>> saves, globals;
  {
    std::lock_guard<std::mutex> lock(request_mutex_);
    relocalization.swap(relocalization_request_);
    saves.swap(save_requests_);
    globals.swap(global_requests_);
  }
  if (relocalization) {
    pipeline_.RequestRelocalization(*relocalization);
    relocalization_pending_ = true;
    ROS_INFO("hylo_node: relocalization requested");
  }
  for (auto& promise : globals) {
    std::string why;
    if (pipeline_.status() == Status::kFailed) {
      why = "the pipeline stopped: " + pipeline_.message();
    } else if (pipeline_.RequestGlobalLocalization(&why)) {
      relocalization_pending_ = true;
      ROS_INFO("hylo_node: global localization requested");
      promise->set_value(
          "searching the whole prior map; no odometry until a pose is accepted "
          "(see ~health)");
      continue;
    }
    promise->set_exception(std::make_exception_ptr(std::runtime_error(why)));
  }
  if (saves.empty()) return;
  std::string path = params_.save_map_path;
  private_nh_.getParam("save_map_path", path);
  for (auto& promise : saves) {
    try {
      promise->set_value(SaveMap(path));
    } catch (...) {
      promise->set_exception(std::current_exception());
    }
  }
}

std::string HyloNode::SaveMap(const std::string& path) {
  const PointCloud points_map = pipeline_.map().Flatten();
  run::WriteWorldCloud(path, points_map, session_.origin_world());
  return "wrote " + std::to_string(points_map.size()) + " points to " + path;
}

void HyloNode::ReportEvents() {
  const std::vector<localization::LocalizationEvent>& events = pipeline_.events();
  for (; events_seen_ < events.size(); ++events_seen_) {
    const localization::LocalizationEvent& e = events[events_seen_];
    last_event_ = localization::ToString(e.kind) + ": " + e.message;
    ROS_INFO("hylo_node: %s", last_event_.c_str());
    if (e.kind == EventKind::kRelocalized || e.kind == EventKind::kRelocalizationFailed ||
        e.kind == EventKind::kInitialized || e.kind == EventKind::kInitializationFailed) {
      relocalization_pending_ = false;
    }
  }
}

void HyloNode::PublishHealth(const odometry::ScanResult* last) {
  // Between scans (initialising, a stalled stream) the last scan's figures are repeated.
  HealthReport& report = health_;
  report.state = StateOf(pipeline_.status(), relocalization_pending_);
  report.localizing = session_.localizing();
  report.backend = config_.BackendName();
  if (last != nullptr) {
    report.t_ns = last->t_ns;
    report.scan = last->health;
    // The update's plane matches, also in SLAM where the fit to the map is not evaluated.
    report.scan.num_matches = last->update.num_matches;
    report.update_applied = last->update.applied;
  }
  report.pipeline = pipeline_.counters();
  report.input = input_.counters();
  report.map_points = pipeline_.map().Size();
  report.last_event = last_event_;
  report.message = pipeline_.message();
  outputs_.PublishHealth(HealthJson(report));
  last_health_ = ros::WallTime::now();
}

void HyloNode::Run() {
  std::vector<ImuSample> imu;
  std::vector<LidarScan> scans;
  // Each result is published as the session produces it; the last one feeds the health topic.
  std::optional<odometry::ScanResult> last;
  std::size_t published = 0;
  session_.OnResult([&](const odometry::ScanResult& r) {
    outputs_.PublishScan(r);
    if (r.pose_status == odometry::PoseStatus::kValid) {
      Eigen::Isometry3d T_world_imu = lie::ToIsometry(r.state.T_map_imu());
      T_world_imu.translation() += session_.origin_world();
      std::lock_guard<std::mutex> lock(request_mutex_);
      last_valid_T_world_imu_ = T_world_imu;
    }
    last = r;
    PointCloud().swap(last->registered_points_map);  // published; the health needs none
    ++published;
  });
  last_health_ = ros::WallTime::now();
  while (ros::ok()) {
    imu.clear();
    scans.clear();
    if (!input_.Pop(&imu, &scans, std::chrono::milliseconds(100))) break;
    ServeRequests();
    published = 0;
    // A failed pipeline (see ~health) takes no more data: its queue would only grow.
    if (!session_.failed()) {
      for (const auto& sample : imu) session_.AddImu(sample);
      for (auto& scan : scans) session_.AddScan(std::move(scan));
    }
    if (published > 0 && outputs_.MapDue(last->t_ns, pipeline_.map().Size())) {
      outputs_.PublishMap(pipeline_.map().Flatten(), last->t_ns);
    }
    ReportEvents();
    if (pipeline_.status() == Status::kFailed && !failure_reported_) {
      ROS_ERROR("hylo_node: the pipeline stopped: %s", pipeline_.message().c_str());
      failure_reported_ = true;
    }
    if (published > 0 || (ros::WallTime::now() - last_health_).toSec() >= 1.0) {
      PublishHealth(published > 0 ? &*last : nullptr);
    }
  }
  input_.Close();
}

}  // namespace hylo::rosnode
