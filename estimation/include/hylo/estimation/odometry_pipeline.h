#pragma once
// The shared lidar(-inertial) odometry loop, the same for every back-end (FAST-LIO2 Fig. 2):
//   measurement queue → static IMU initialisation → undistortion → voxel downsampling
//   → Estimator::Update against the map's planes → add the registered scan to the map.
// Localization in a prior map adds, for every back-end alike, the ICP initializer at the
// start, hybrid map updates, health checks and relocalization (localization.h).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hylo/estimation/estimator.h"
#include "hylo/estimation/imu_initializer.h"
#include "hylo/estimation/localization.h"
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
  int point_stride = 1;             ///< before the voxel, keep every n-th return of each ring
                                    ///< (FAST-LIO2's point_filter_num): less work per scan
                                    ///< on dense sensors, sparser far surfaces (>= 1)
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
  bool update_map = true;                ///< SLAM (no prior map): add registered scans to the
                                         ///< map. With a prior, localization.update_after_s rules
  LocalizationOptions localization;      ///< used once SetPriorMap + SetInitialGuess are called
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
  /// Body-frame twist of the IMU at t_ns: linear = R_map_imuᵀ v_map_imu (m/s), angular = the
  /// last gyro sample minus its bias (rad/s; without IMU, from the last two poses).
  Eigen::Vector3d linear_velocity_imu = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_imu = Eigen::Vector3d::Zero();
  /// 6×6 twist covariance, order [v (IMU frame, m/s); ω (IMU frame, rad/s)].
  Eigen::Matrix<double, 6, 6> twist_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  /// REP-105 odom frame: T_map_imu = T_map_odom · T_odom_imu, where T_odom_imu stays continuous
  /// and relocalization jumps go into T_map_odom (identity until the first relocalization).
  lie::SE3d T_map_odom;
  ScanHealth health;  ///< fit to the map after the update (localization; also filled in SLAM)
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
  std::size_t scans_initializer = 0;  ///< consumed by the ICP initializer (start, relocalization)
  std::size_t scans_bad_health = 0;   ///< scans whose ScanHealth was not good
};

class OdometryPipeline {
 public:
  /// kInitializing: IMU at rest / ICP initializer; kRunning; kLost: running, but health was
  /// bad for lost_after_scans scans and a relocalization is pending; kFailed: see message().
  enum class Status { kInitializing, kRunning, kLost, kFailed };

  /// Throws hylo::InternalError naming the field when `options` is not valid.
  explicit OdometryPipeline(const OdometryPipelineOptions& options);

  void AddImu(const ImuSample& sample) { queue_.AddImu(sample); }
  void AddScan(LidarScan scan) { queue_.AddScan(std::move(scan)); }

  /// Localization: the prior map (map frame, downsampled by the caller, e.g. BuildPriorMap)
  /// and the guess of T_map_imu at the start (with an IMU only its yaw and position are used:
  /// roll and pitch come from gravity). Both before the first scan; then odometry starts only
  /// from a pose the ICP initializer accepted, or the pipeline fails with the reason.
  void SetPriorMap(const registration::PointCloud& points_map);
  void SetInitialGuess(const Eigen::Isometry3d& T_map_imu_guess);
  /// Relocalize around `T_map_imu_guess` with the next scan (e.g. ROS /initialpose). Before
  /// the start it replaces the initial guess. Needs a prior map.
  void RequestRelocalization(const Eigen::Isometry3d& T_map_imu_guess);
  /// True when a prior map and an initial guess were given.
  bool localizing() const { return localizing_; }
  /// Start, loss, relocalization and hybrid events in time order.
  const std::vector<LocalizationEvent>& events() const { return events_; }

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
  bool Initialize(const MeasurementGroup& group);  // true: the group's scan was consumed
  bool ProcessScan(MeasurementGroup* group, ScanResult* result);
  void FillTwist(const MeasurementGroup& group, ScanResult* result);
  // odometry_pipeline_localization.cpp
  bool AccumulateStaticScan(const MeasurementGroup& group);
  void StartFromIcp(const MeasurementGroup& group);
  bool MapUpdateAllowed(int64_t t_ns, const ScanResult& result);
  void CheckHealth(const LidarScan& scan, const DeskewedScan& scan_downsampled,
                   const std::vector<int64_t>& imu_knots, ScanResult* result);
  bool Relocalize(const LidarScan& scan, const std::vector<int64_t>& imu_knots,
                  const Eigen::Isometry3d& T_map_imu_guess);
  void AddEvent(LocalizationEvent::Kind kind, int64_t t_ns, const std::string& message,
                const registration::IcpInitializerResult* icp = nullptr);

  OdometryPipelineOptions options_;
  MeasurementQueue queue_;
  ImuInitializer initializer_;
  std::unique_ptr<Estimator> estimator_;
  mapping::MapManager map_;
  registration::PlaneMatcher matcher_;
  Status status_ = Status::kInitializing;
  std::string message_;
  PipelineCounters counters_;
  Eigen::Vector3d last_gyro_imu_ = Eigen::Vector3d::Zero();  // last sample, rad/s
  double imu_period_s_ = 0.005;        // measured IMU sample period, s
  bool have_previous_result_ = false;  // for the no-IMU angular velocity
  NavState previous_state_;
  PoseCovariance6 previous_pose_covariance_ = PoseCovariance6::Zero();

  // Localization (odometry_pipeline_localization.cpp).
  registration::IcpInitializer icp_initializer_;
  bool localizing_ = false;
  bool have_prior_ = false;
  Eigen::Isometry3d T_map_imu_guess_ = Eigen::Isometry3d::Identity();
  registration::PointCloud static_cloud_imu_;  // accumulated static scans, IMU frame
  int static_scans_ = 0;
  int64_t static_end_t_ns_ = 0;                // last IMU stamp of the static scans
  bool has_relocalize_request_ = false;
  Eigen::Isometry3d relocalize_guess_ = Eigen::Isometry3d::Identity();
  int bad_scans_in_row_ = 0;
  int scans_until_retry_ = 0;
  int64_t localization_start_ns_ = 0;
  bool hybrid_started_ = false;
  lie::SE3d T_map_odom_;
  std::vector<LocalizationEvent> events_;
};

}  // namespace hylo::estimation
