#pragma once
// The shared lidar(-inertial) odometry loop, the same for every back-end (FAST-LIO2 Fig. 2):
//   measurement queue → static IMU initialisation → undistortion → voxel downsampling
//   → Estimator::Update against the map's planes → add the registered scan to the map.
// Localization in a prior map (issue 6) reuses it: MapManager::SetPrior, update_map.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hylo/estimation/estimator.h"
#include "hylo/estimation/imu_initializer.h"
#include "hylo/estimation/measurement_queue.h"
#include "hylo/mapping/map_manager.h"
#include "hylo/registration/plane_matcher.h"

namespace hylo::estimation {

/// Scan clean-up before registration (section `preprocess:`).
struct PreprocessOptions {
  double min_range_m = 0.5;         ///< closer returns are dropped (vehicle body), m (>= 0)
  double max_range_m = 100.0;       ///< farther returns are dropped, m (> min_range_m)
  double max_point_offset_s = 0.2;  ///< per-point times beyond this after the start are bad, s
  double scan_voxel_m = 0.5;        ///< uniform-sampling voxel of the scan, m (0 = keep all)
  int min_points = 100;             ///< fewer points after clean-up: the scan is skipped
  bool deskew = true;               ///< undistort with the IMU (always off without IMU)
  bool IsValid(std::string* why) const;
};

struct OdometryPipelineOptions {
  Estimator::Options estimator;          ///< back-end and its settings (use_imu lives here)
  double gravity_mps2 = 9.81;            ///< local gravity, m/s²
  ImuInitializerOptions init;            ///< static initialisation
  MeasurementQueueOptions queue;         ///< gap threshold (use_imu is taken from estimator)
  PreprocessOptions preprocess;
  registration::PlaneMatcherOptions planes;
  mapping::MapManagerOptions map;
  lie::SE3d T_imu_lidar;                 ///< extrinsic (the filter may refine it online)
  bool update_map = true;                ///< add registered scans to the map (SLAM)
  double registered_scan_voxel_m = 0.0;  ///< > 0: each result carries the whole scan, uniformly
                                         ///< sampled at this voxel (m), deskewed and registered
                                         ///< in the map frame, for dense map outputs; 0 = off
  bool IsValid(std::string* why) const;
};

/// One processed scan, stamped at its end.
struct ScanResult {
  int64_t t_ns = 0;                  ///< scan end, ns
  NavState state;                    ///< after the update
  PoseCovariance6 pose_covariance = PoseCovariance6::Zero();
  UpdateSummary update;
  std::size_t raw_points = 0;        ///< after clean-up
  std::size_t downsampled_points = 0;
  std::size_t map_points = 0;        ///< after the map update
  bool map_updated = false;
  double deskew_ms = 0.0, update_ms = 0.0, map_ms = 0.0, total_ms = 0.0;  ///< wall time
  double cpu_ms = 0.0;  ///< CPU time of this thread for the whole scan (robust to a busy host)
  /// The scan in the map frame at registered_scan_voxel_m (empty when that option is 0 or the
  /// update was not applied: an unregistered scan must not smear a dense map).
  registration::PointCloud registered_points_map;
};

struct PipelineCounters {
  QueueCounters queue;
  std::size_t scans_before_init = 0;  ///< dropped while the IMU initialised
  std::size_t scans_too_small = 0;    ///< fewer than preprocess.min_points
  std::size_t scans_processed = 0;
  std::size_t scans_not_applied = 0;  ///< update not applied (too few matches, ...)
  std::size_t scans_degenerate = 0;
  std::size_t points_dropped_sanitize = 0;
};

class OdometryPipeline {
 public:
  enum class Status { kInitializing, kRunning, kFailed };

  /// Throws hylo::InternalError naming the field when `options` is not valid.
  explicit OdometryPipeline(const OdometryPipelineOptions& options);

  void AddImu(const ImuSample& sample) { queue_.AddImu(sample); }
  void AddScan(LidarScan scan) { queue_.AddScan(std::move(scan)); }

  /// Processes every scan that is ready and appends one result per processed scan. `flush`
  /// at the end of a log releases scans whose IMU ends early.
  void Process(std::vector<ScanResult>* results, bool flush = false);

  Status status() const { return status_; }
  /// Why the pipeline failed (kFailed), e.g. the vehicle moved during initialisation.
  const std::string& message() const { return message_; }
  PipelineCounters counters() const;
  const mapping::MapManager& map() const { return map_; }
  mapping::MapManager& map() { return map_; }
  const Estimator& estimator() const { return *estimator_; }

 private:
  void Initialize(const MeasurementGroup& group);
  bool ProcessScan(MeasurementGroup* group, ScanResult* result);

  OdometryPipelineOptions options_;
  MeasurementQueue queue_;
  ImuInitializer initializer_;
  std::unique_ptr<Estimator> estimator_;
  mapping::MapManager map_;
  registration::PlaneMatcher matcher_;
  Status status_ = Status::kInitializing;
  std::string message_;
  PipelineCounters counters_;
};

}  // namespace hylo::estimation
