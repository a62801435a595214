#pragma once
// The one driver of the odometry pipeline, shared by every front end: the command line's runs
// (run_log.h), the ROS node, the Python package and the tests' simulated drives. A front end
// only moves data: it hands the session IMU samples and scans in arrival order, from a log, a
// topic or memory, and reads what the session keeps.
//
// A session owns the pipeline (and, in localization, the prior map's local origin: the
// pipeline computes near zero, everything a session hands out in the world frame is the
// map's own), collects each scan's result and the back-end's finalized states, thins the
// registered scans into a dense map, and calls the front end back with every result as it is
// produced (a live consumer publishes it then).

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/common/sensor_data.h"
#include "hylo/io/trajectory_io.h"
#include "hylo/mapping/prior_map.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::run {

/// What a session keeps besides the pipeline. A live run keeps neither: its memory stays flat
/// and the result callback sees every scan.
struct SessionKeeps {
  bool results = true;    ///< every scan's result (without its points), for outputs at the end
  bool dense_map = true;  ///< the registered scans thinned at output.dense_map_voxel_m
  bool finalized = true;  ///< the back-end's finalized states
};

class Session {
 public:
  /// Throws hylo::InternalError naming the field when `options` is not valid.
  explicit Session(const odometry::OdometryPipelineOptions& options, SessionKeeps keeps = {});

  // --- localization in a prior map: before the first scan ---
  /// Reads the map at `path` (a point cloud file, or a tiled map directory streamed around the
  /// vehicle), thins it with `options` and starts localization from `T_world_imu_guess` (the
  /// map file's frame; none: the whole map is searched). Throws naming the file when it cannot
  /// be read or holds no point.
  void LoadPriorMap(const std::string& path, const mapping::PriorMapOptions& options,
                    const std::optional<Eigen::Isometry3d>& T_world_imu_guess);
  /// The same for a map held in memory (world frame, m). Throws std::invalid_argument when it
  /// has no finite point.
  void SetPriorMap(const std::vector<Eigen::Vector3d>& points_world,
                   const mapping::PriorMapOptions& options,
                   const std::optional<Eigen::Isometry3d>& T_world_imu_guess);

  /// Called with every scan's result as it is produced: live state, registered points in the
  /// map frame when output.dense_map_voxel_m > 0 (before the session folds them into its
  /// dense map and drops them).
  void OnResult(std::function<void(const odometry::ScanResult&)> callback) {
    on_result_ = std::move(callback);
  }

  /// Called with every state the back-end finalizes, oldest first (map frame).
  void OnFinalized(std::function<void(const estimation::NavState&)> callback) {
    on_finalized_ = std::move(callback);
  }

  // --- data, in arrival order ---
  /// Adds an IMU sample; a scan that waited for it (its sweep's end covered) is processed at
  /// once rather than when the next scan comes.
  void AddImu(const ImuSample& sample);
  /// Adds a scan and processes every scan that is ready. A failed pipeline takes no more
  /// data (failed() says so; its queue would only grow).
  void AddScan(LidarScan scan);
  /// The data ended: processes what is left and finalizes every state.
  void Finish();

  // --- what the session holds ---
  odometry::OdometryPipeline& pipeline() { return pipeline_; }
  const odometry::OdometryPipeline& pipeline() const { return pipeline_; }
  bool failed() const;
  bool localizing() const { return localizing_; }
  /// The prior map (empty in SLAM): its origin, counts, tiled directory.
  const mapping::PriorMap& prior() const { return prior_; }
  /// World position of the map frame's zero (the prior's origin; zero in SLAM), m.
  const Eigen::Vector3d& origin_world() const { return prior_.origin_world; }
  /// Every processed scan's result, without its points (SessionKeeps::results).
  const std::vector<odometry::ScanResult>& results() const { return results_; }
  /// The back-end's finalized states, oldest first (map frame; SessionKeeps::finalized).
  const std::vector<estimation::NavState>& finalized() const { return finalized_; }
  /// The registered scans thinned at output.dense_map_voxel_m, map frame (empty when 0).
  const PointCloud& dense_map() const;
  /// T_world_imu of the finalized states, and of the live states of the results whose pose is
  /// a place in the map (PoseStatus::kValid).
  std::vector<io::StampedPose> Trajectory() const;
  std::vector<io::StampedPose> LiveTrajectory() const;
  /// The live states of the other results: lost (map frame, not to be trusted) or provisional
  /// (the search's own frame, shifted by the map's origin like the rest).
  std::vector<io::StampedPose> ProvisionalTrajectory() const;
  std::size_t scans_added() const { return scans_added_; }
  std::size_t scans_processed() const { return scans_processed_; }
  /// Wall time since the session was constructed, s.
  double ElapsedSeconds() const;
  /// Wall time from the session's construction to the first pose, s, and the process's CPU
  /// time by then (every thread), s; NaN before the first pose.
  double first_pose_after_s() const { return first_pose_after_s_; }
  double first_pose_cpu_s() const { return first_pose_cpu_s_; }

 private:
  void Collect(std::vector<odometry::ScanResult>* fresh);

  odometry::OdometryPipeline pipeline_;
  SessionKeeps keeps_;
  bool localizing_ = false;
  mapping::PriorMap prior_;
  std::function<void(const odometry::ScanResult&)> on_result_;
  std::function<void(const estimation::NavState&)> on_finalized_;
  std::optional<registration::UniformSampler> dense_map_;
  std::vector<odometry::ScanResult> results_;
  std::vector<estimation::NavState> finalized_;
  std::size_t scans_added_ = 0;
  std::size_t scans_processed_ = 0;
  double start_wall_s_ = 0.0;
  double first_pose_after_s_;
  double first_pose_cpu_s_;
};

/// The process's CPU time so far (every thread), s.
double ProcessCpuSeconds();

}  // namespace hylo::run
