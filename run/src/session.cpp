#include "hylo/run/session.h"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "hylo/run/prior_map_io.h"
#include "run_outputs.h"

namespace hylo::run {
namespace {

double WallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

double ProcessCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

Session::Session(const odometry::OdometryPipelineOptions& options, SessionKeeps keeps)
    : pipeline_(options),
      keeps_(keeps),
      start_wall_s_(WallSeconds()),
      first_pose_after_s_(std::numeric_limits<double>::quiet_NaN()),
      first_pose_cpu_s_(std::numeric_limits<double>::quiet_NaN()) {
  // A hash of voxels, not a tree: nothing searches this map during the run, and the tree's
  // downsampling insert cost as much per scan as the odometry.
  const double voxel_m = options.output.dense_map_voxel_m;
  if (keeps.dense_map && voxel_m > 0.0) dense_map_.emplace(static_cast<float>(voxel_m));
}

void Session::LoadPriorMap(const std::string& path, const mapping::PriorMapOptions& options,
                           const std::optional<Eigen::Isometry3d>& T_world_imu_guess) {
  prior_ = run::LoadPriorMap(path, options, T_world_imu_guess, &pipeline_);
  localizing_ = true;
}

void Session::SetPriorMap(const std::vector<Eigen::Vector3d>& points_world,
                          const mapping::PriorMapOptions& options,
                          const std::optional<Eigen::Isometry3d>& T_world_imu_guess) {
  prior_ = mapping::BuildPriorMap(points_world, options);
  pipeline_.SetPriorMap(prior_.points_local);
  std::optional<Eigen::Isometry3d> guess_local;
  if (T_world_imu_guess) guess_local = mapping::PoseToLocal(*T_world_imu_guess, origin_world());
  pipeline_.SetInitialGuess(guess_local);
  localizing_ = true;
}

double Session::ElapsedSeconds() const { return WallSeconds() - start_wall_s_; }

bool Session::failed() const {
  return pipeline_.status() == odometry::OdometryPipeline::Status::kFailed;
}

void Session::AddImu(const ImuSample& sample) {
  if (failed()) return;
  pipeline_.AddImu(sample);
  if (pipeline_.scans_waiting() == 0) return;
  std::vector<odometry::ScanResult> fresh;
  pipeline_.Process(&fresh);
  Collect(&fresh);
}

void Session::AddScan(LidarScan scan) {
  if (failed()) return;
  ++scans_added_;
  pipeline_.AddScan(std::move(scan));
  std::vector<odometry::ScanResult> fresh;
  pipeline_.Process(&fresh);
  Collect(&fresh);
}

void Session::Finish() {
  std::vector<odometry::ScanResult> fresh;
  pipeline_.Finish(&fresh);
  Collect(&fresh);
}

void Session::Collect(std::vector<odometry::ScanResult>* fresh) {
  if (!fresh->empty() && std::isnan(first_pose_after_s_)) {
    first_pose_after_s_ = WallSeconds() - start_wall_s_;
    first_pose_cpu_s_ = ProcessCpuSeconds();
  }
  for (odometry::ScanResult& result : *fresh) {
    ++scans_processed_;
    if (on_result_) on_result_(result);
    if (dense_map_ && !result.registered_points_map.empty()) {
      dense_map_->Add(result.registered_points_map);
    }
    PointCloud().swap(result.registered_points_map);
    if (keeps_.results) results_.push_back(std::move(result));
  }
  for (estimation::NavState& x : pipeline_.TakeFinalizedStates()) {
    if (on_finalized_) on_finalized_(x);
    if (keeps_.finalized) finalized_.push_back(x);
  }
}

const PointCloud& Session::dense_map() const {
  static const PointCloud kNone;
  return dense_map_ ? dense_map_->points() : kNone;
}

std::vector<io::StampedPose> Session::Trajectory() const {
  return WorldTrajectory(finalized_, origin_world());
}

std::vector<io::StampedPose> Session::LiveTrajectory() const {
  return WorldTrajectory(LiveStates(results_, /*valid=*/true), origin_world());
}

std::vector<io::StampedPose> Session::ProvisionalTrajectory() const {
  return WorldTrajectory(LiveStates(results_, /*valid=*/false), origin_world());
}

}  // namespace hylo::run
