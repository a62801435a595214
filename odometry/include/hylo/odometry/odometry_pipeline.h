#pragma once
// The shared lidar(-inertial) odometry loop, the same for every back-end (FAST-LIO2 Fig. 2):
//   measurement queue → static IMU initialisation → scan preprocessing (clean-up, sampling,
//   undistortion) → Estimator::Update against the map's planes → add the registered scan to
//   the map.
// Localization in a prior map adds, for every back-end alike, a LocalizationSupervisor: the ICP
// start, health checks from the update's residuals, relocalization and hybrid map updates.

#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "hylo/estimation/estimator.h"
#include "hylo/estimation/estimator_options.h"
#include "hylo/estimation/imu_initializer.h"
#include "hylo/estimation/imu_options.h"
#include "hylo/estimation/initial_uncertainty.h"
#include "hylo/localization/global_search.h"
#include "hylo/localization/localization.h"
#include "hylo/localization/supervisor.h"
#include "hylo/mapping/map_manager.h"
#include "hylo/odometry/data_gap.h"
#include "hylo/odometry/measurement_queue.h"
#include "hylo/odometry/scan_preprocessor.h"
#include "hylo/odometry/scan_result.h"
#include "hylo/odometry/twist.h"
#include "hylo/registration/parallel.h"
#include "hylo/registration/plane_matcher.h"

namespace hylo::odometry {

/// What the pipeline produces beyond the poses (section `output:` of a run configuration).
struct PipelineOutputOptions {
  /// > 0: each result carries the whole scan, uniformly sampled at this voxel (m), deskewed and
  /// registered in the map frame, for dense map outputs; 0 = off. Finer than 0.01 m keeps
  /// every return and exhausts memory on long runs.
  double dense_map_voxel_m = 0.0;
  bool IsValid(std::string* why) const;
};

/// The lidar's clock (section `lidar:` of a run configuration, beside the log's topic).
struct PipelineLidarOptions {
  /// Constant offset of the IMU's clock from the lidar's: t_imu = t_lidar + time_offset_s, s
  /// (FAST-LIO's `time_offset_lidar_to_imu`, the same sign). Scans are moved onto the IMU
  /// clock as they enter the pipeline, so every output is stamped in the IMU clock. At most
  /// 1 s: a larger constant is not a latency but another time base (e.g. time since boot
  /// against Unix time), which a constant cannot correct and which would pair every scan with
  /// IMU data from elsewhere in the log.
  double time_offset_s = 0.0;
  bool IsValid(std::string* why) const;
  int64_t TimeOffsetNs() const;
};

/// Every setting of the pipeline. Member names are the run configuration's sections, so a
/// message from IsValid names the key a user wrote (the estimator's sections sit at the top
/// level of the configuration: `backend`, `lidar_update`, `no_imu`, `ieskf`, `sliding_window`).
struct OdometryPipelineOptions {
  estimation::ImuOptions imu;                            ///< the inertial sensor, or none
  PipelineLidarOptions lidar;                ///< the lidar's clock offset
  estimation::EstimatorOptions estimator;                ///< back-end and its settings
  estimation::InitialUncertainty initial_uncertainty;    ///< how a back-end starts
  estimation::ImuInitializerOptions init;                ///< static IMU initialisation
  PreprocessOptions preprocess;              ///< scan clean-up, sampling, deskewing
  registration::PlaneMatcherOptions planes;  ///< point-to-plane association
  mapping::MapManagerOptions map;            ///< the map registered against
  localization::LocalizationOptions localization;          ///< used once SetInitialGuess is called
  PipelineOutputOptions output;              ///< dense registered scans
  lie::SE3d T_imu_lidar;                     ///< extrinsic (the filter may refine it online)
  bool update_map = true;                    ///< SLAM (no prior map): add registered scans to
                                             ///< the map. With a prior, update_after_s rules
  /// Threads for a scan's per-point work (preprocessing, plane association, the residuals of
  /// both back-ends): 0 = every core, 1 = the calling thread alone. The results are the same
  /// for every value (each point's work writes only its own outputs; sums run in point order).
  int threads = 0;
  bool IsValid(std::string* why) const;

 private:
  bool CheckCalibrationHasImu(std::string* why) const;
};

class OdometryPipeline {
 public:
  /// kInitializing: IMU at rest / ICP initializer / searching while moving (no pose in the
  /// map yet: a search's results are provisional, see ScanResult::pose_status); kRunning; kLost: running, but health was bad for lost_after_scans
  /// scans and a relocalization is pending; kFailed: see message().
  enum class Status { kInitializing, kRunning, kLost, kFailed };

  /// Throws hylo::InternalError naming the field when `options` is not valid.
  explicit OdometryPipeline(const OdometryPipelineOptions& options);
  ~OdometryPipeline();

  /// Queues the sample. When no scan has come for longer than a data gap, the estimator's
  /// state is carried on with the IMU meanwhile (Estimator::CarryForward), so the first scan
  /// after a long lidar gap does not pay for the whole gap's propagation.
  void AddImu(const ImuSample& sample);
  /// Scans queued and not processed yet (waiting for the IMU to cover their sweep).
  std::size_t scans_waiting() const { return queue_.pending_scans(); }
  /// The scan's stamps are moved onto the IMU clock here (lidar.time_offset_s).
  void AddScan(LidarScan scan);

  /// Localization: the prior map (map frame, downsampled by the caller, e.g. BuildPriorMap;
  /// its global-localization raster is built here) and the guess of T_map_imu at the start
  /// (with an IMU only its yaw and position are used: roll and pitch come from gravity), or
  /// std::nullopt to search the whole map. Both before the first scan, the map first; then
  /// odometry starts only from a pose the ICP initializer accepted, or the pipeline fails with
  /// the reason.
  void SetPriorMap(const PointCloud& points_map);
  /// Localization in a streamed prior instead (mapping/streamed_prior.h, e.g. a tiled map;
  /// the map frame is its local frame): each scan posts the position to it and it swaps in
  /// what it finished loading (a failed load fails the pipeline with its reason); the start
  /// and a lost vehicle read the rest on demand. The global localizer's raster is built from
  /// `overview_points` (the map thinned for it; empty: no global search). Off the map the
  /// supervisor runs odometry only (events left_map / reentered_map). Before the first scan,
  /// as SetPriorMap.
  void SetStreamedPriorMap(std::shared_ptr<mapping::StreamedPrior> prior,
                           const PointCloud& overview_points);
  void SetInitialGuess(const std::optional<Eigen::Isometry3d>& T_map_imu_guess);
  /// Relocalize around `T_map_imu_guess` with the next scan (e.g. ROS /initialpose). Before
  /// the start it replaces the initial guess. Needs a prior map.
  void RequestRelocalization(const Eigen::Isometry3d& T_map_imu_guess);
  /// Forget the pose and search the whole prior map (LocalizationSupervisor::
  /// RequestGlobalLocalization). False with *why without a prior map or a global map.
  bool RequestGlobalLocalization(std::string* why);
  /// True when SetInitialGuess was called (localization in a prior map).
  bool localizing() const { return supervisor_ != nullptr; }
  /// Start, loss, relocalization and hybrid events in time order.
  const std::vector<localization::LocalizationEvent>& events() const;

  /// Processes every scan that is ready and appends one result per processed scan. `flush`
  /// at the end of a log releases scans whose IMU ends early.
  void Process(std::vector<ScanResult>* results, bool flush = false);
  /// The log ended: processes what is left (as Process with flush) and finalizes every state.
  void Finish(std::vector<ScanResult>* results);
  /// The states the back-end finalized since the last call, oldest first, one per updated
  /// scan whose pose is a place in the map (PoseStatus::kValid; see Estimator: with the
  /// smoother they lag the live results by its window).
  std::vector<estimation::NavState> TakeFinalizedStates();

  Status status() const;
  /// Why the pipeline failed (kFailed), e.g. the vehicle moved during initialisation.
  const std::string& message() const { return message_; }
  PipelineCounters counters() const;
  const mapping::MapManager& map() const { return map_; }
  mapping::MapManager& map() { return map_; }
  const estimation::Estimator& estimator() const { return *estimator_; }
  const OdometryPipelineOptions& options() const { return options_; }

 private:
  // odometry_pipeline_start.cpp: true when the group's scan was consumed by the start.
  bool Start(const MeasurementGroup& group);
  bool StartWithoutImu(const MeasurementGroup& group);
  std::size_t FeedImuInitializer(const MeasurementGroup& group);
  void StartSlam(const estimation::NavState& x, const std::vector<ImuSample>& imu_after);
  void StartMoving(const MeasurementGroup& group, const std::vector<ImuSample>& imu_after);
  PointCloud ScanInImu(const MeasurementGroup& group);  // cleaned, IMU frame
  void AddStaticScan(const MeasurementGroup& group);
  void StartLocalization(const MeasurementGroup& group);
  // odometry_pipeline_gaps.cpp
  // No scan for longer than a data gap, the IMU running: the estimator is carried forward on
  // the samples that no scan can need any more.
  void CarryThroughLidarGap();
  // Localizing, before the scan ending at `scan_end_ns` with IMU data `imu`, after a gap in
  // both lidar and IMU: restarts the estimator for the supervisor to check (true) instead of
  // tracking from a state propagated blind through the gap.
  bool RestartAfterBlindGap(int64_t scan_end_ns, const std::vector<ImuSample>& imu);
  // Localizing in the prior, the scan ending at `scan_end_ns` comes after a gap in the data
  // (ScanIntervalClock): its pose is the one propagated through the gap, for a fit to confirm.
  bool AfterDataGapInMap(int64_t scan_end_ns) const;
  void Fail(const std::string& why);
  // A tiled prior before each scan: the loader's news, its failures, on or off the tiles.
  bool FollowStreamedPrior();
  // odometry_pipeline.cpp
  void ProcessQueued(std::vector<ScanResult>* results, bool flush);  // Process, on threads_
  bool ProcessScan(MeasurementGroup* group, ScanResult* result);
  void UpdateMap(const estimation::DeskewedScan& scan, ScanResult* result);
  void CollectFinalized();  // the back-end's finalized states; pending scans into the map

  OdometryPipelineOptions options_;
  MeasurementQueue queue_;
  estimation::ImuInitializer imu_initializer_;
  ScanPreprocessor preprocessor_;
  std::unique_ptr<estimation::Estimator> estimator_;
  mapping::MapManager map_;
  registration::PlaneMatcher matcher_;
  std::unique_ptr<registration::ThreadLimit> threads_;         // options_.threads, around Process
  std::unique_ptr<localization::GlobalSearch> global_search_;  // with a prior map
  // Declared after the map and the global search it reads: destroyed first, it waits for a
  // global attempt still running on its worker thread before they go.
  std::unique_ptr<localization::LocalizationSupervisor> supervisor_;   // null in SLAM
  TwistEstimator twist_;
  Status status_ = Status::kInitializing;  // kLost is the supervisor's
  std::string message_;
  PipelineCounters counters_;
  std::set<int64_t> untrusted_t_ns_;  // scans not kValid whose states are not finalized yet
  // Scans whose pose the supervisor replaced after their update (a relocalization): the
  // back-end finalizes the state of the update, which the trajectory must not hold.
  std::map<int64_t, estimation::NavState> replaced_;
  // A scan accepted for the map joins it once the back-end has finalized its state, at that
  // state: the smoother's map then holds smoothed poses, not the live ones it revises (the
  // filter finalizes at once, so its scans join as before).
  struct PendingMapScan {
    int64_t t_ns = 0;
    PointCloud points_lidar;
  };
  std::deque<PendingMapScan> map_pending_;
  std::vector<estimation::NavState> finalized_;  // collected, not yet taken
  ScanIntervalClock scan_clock_;  // gaps in the data (localization)
};

}  // namespace hylo::odometry
