// The odometry loop: options, the per-scan flow and the outputs (the start is in
// odometry_pipeline_start.cpp).
#include "hylo/odometry/odometry_pipeline.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "hylo/common/check.h"
#include "hylo/common/option_checks.h"
#include "hylo/common/time.h"
#include "hylo/common/transformed_cloud.h"
#include "hylo/lie/isometry.h"

namespace hylo::odometry {
namespace {

MeasurementQueueOptions QueueOptions(const estimation::ImuOptions& imu) {
  MeasurementQueueOptions q;
  q.use_imu = imu.enabled;
  q.imu_gap_ns = imu.GapNs();
  q.accel_range_mps2 = imu.accel_range_mps2;
  q.gyro_range_radps = imu.gyro_range_radps;
  return q;
}

double CpuMs(clockid_t clock = CLOCK_THREAD_CPUTIME_ID) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

double MsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// The whole sweep undistorted to its end, in the IMU frame: what recovery accumulates and
// places in the map.
PointCloud SweepImu(const estimation::SweepMotion& motion, const LidarScan& cleaned,
                    const lie::SE3d& T_imu_lidar) {
  return Transformed(T_imu_lidar, motion.ToSweepEnd(cleaned));
}

}  // namespace

bool PipelineOutputOptions::IsValid(std::string* why) const {
  if (!CheckNonNegative("dense_map_voxel_m", dense_map_voxel_m, why)) return false;
  if (dense_map_voxel_m > 0.0 && dense_map_voxel_m < 0.01) {
    return FailOption("dense_map_voxel_m", dense_map_voxel_m,
                      "must be 0 (off) or >= 0.01 m (finer voxels keep every return and "
                      "exhaust memory)",
                      why);
  }
  return true;
}

bool PipelineLidarOptions::IsValid(std::string* why) const {
  if (std::isfinite(time_offset_s) && std::abs(time_offset_s) <= 1.0) return true;
  return FailOption("time_offset_s", time_offset_s,
                    "must be finite and within [-1, 1] s: a larger offset is another time base "
                    "(fix the driver's clock), not a latency a constant can correct",
                    why);
}

int64_t PipelineLidarOptions::TimeOffsetNs() const { return SecondsToNanos(time_offset_s); }

bool OdometryPipelineOptions::IsValid(std::string* why) const {
  return CheckSection(imu, "imu", why) && CheckSection(lidar, "lidar", why) &&
         estimator.IsValid(why) && CheckSection(initial_uncertainty, "initial_uncertainty", why) &&
         CheckSection(init, "init", why) && CheckSection(preprocess, "preprocess", why) &&
         CheckSection(planes, "planes", why) && CheckSection(map, "map", why) &&
         CheckSection(localization, "localization", why) && CheckSection(output, "output", why) &&
         CheckAtLeast("threads", threads, 0, "(0 = every core, 1 = the calling thread alone)",
                      why) &&
         CheckCalibrationHasImu(why);
}

bool OdometryPipelineOptions::CheckCalibrationHasImu(std::string* why) const {
  // The time offset and the extrinsic rotation are seen only against the IMU's motion.
  const estimation::SlidingWindowOptions& window = estimator.sliding_window;
  if (imu.enabled || estimator.backend != estimation::Estimator::Backend::kSlidingWindow ||
      !window.EstimatesCalibration()) {
    return true;
  }
  return FailOption(window.estimate_time_offset ? "sliding_window.estimate_time_offset"
                                                : "sliding_window.estimate_extrinsic_rotation",
                    "true", "needs the IMU (imu: none leaves nothing to calibrate against)", why);
}

OdometryPipeline::OdometryPipeline(const OdometryPipelineOptions& options)
    : options_(options),
      queue_(QueueOptions(options.imu)),
      imu_initializer_(options.init, options.imu.gravity_mps2),
      preprocessor_(options.preprocess, options.imu.enabled),
      estimator_(estimation::Estimator::Create(options.estimator, options.imu)),
      map_(options.map),
      matcher_(map_, options.planes),
      twist_(options.imu) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("invalid options: " + why);
  threads_ = std::make_unique<registration::ThreadLimit>(options_.threads);
}

OdometryPipeline::~OdometryPipeline() = default;

void OdometryPipeline::AddScan(LidarScan scan) {
  // Point times are offsets from the scan start, so the two stamps carry the whole shift.
  const int64_t offset_ns = options_.lidar.TimeOffsetNs();
  scan.t_ns += offset_ns;
  scan.end_t_ns += offset_ns;
  queue_.AddScan(std::move(scan));
}

const std::vector<localization::LocalizationEvent>& OdometryPipeline::events() const {
  static const std::vector<localization::LocalizationEvent> kNone;
  return supervisor_ ? supervisor_->events() : kNone;
}

OdometryPipeline::Status OdometryPipeline::status() const {
  if (status_ == Status::kRunning && supervisor_ && supervisor_->searching()) {
    return Status::kInitializing;  // no pose in the map yet
  }
  if (status_ == Status::kRunning && supervisor_ && supervisor_->lost()) return Status::kLost;
  return status_;
}

PipelineCounters OdometryPipeline::counters() const {
  PipelineCounters c = counters_;
  c.queue = queue_.counters();
  if (supervisor_) {
    c.scans_initializer = supervisor_->scans_initializer();
    c.scans_bad_health = supervisor_->scans_bad_health();
  }
  return c;
}

void OdometryPipeline::Process(std::vector<ScanResult>* results, bool flush) {
  threads_->Run([&] { ProcessQueued(results, flush); });
}

void OdometryPipeline::ProcessQueued(std::vector<ScanResult>* results, bool flush) {
  MeasurementGroup group;
  while (status_ != Status::kFailed && queue_.Pop(&group, flush)) {
    if (status_ == Status::kInitializing) {
      const std::size_t before = counters().scans_initializer;
      if (Start(group)) {
        if (counters().scans_initializer == before) ++counters_.scans_before_init;
        continue;
      }
    }
    ScanResult result;
    if (ProcessScan(&group, &result)) results->push_back(std::move(result));
  }
  // A log that ends while the initializer still waits for static scans: register what there
  // is rather than end without a pose.
  if (flush && status_ == Status::kInitializing && supervisor_ && supervisor_->static_scans() > 0 &&
      imu_initializer_.status() == estimation::ImuInitializer::Status::kDone) {
    StartLocalization(MeasurementGroup());
  }
  if (flush && status_ == Status::kRunning && supervisor_ && supervisor_->searching() &&
      !supervisor_->started()) {
    Fail("no start pose: the log ended while searching (" + supervisor_->events().back().message +
         ")");
  }
}

void OdometryPipeline::Finish(std::vector<ScanResult>* results) {
  Process(results, /*flush=*/true);
  threads_->Run([&] { estimator_->Finish(); });
  CollectFinalized();  // the smoother's last window joins the map
}

std::vector<estimation::NavState> OdometryPipeline::TakeFinalizedStates() {
  CollectFinalized();
  std::vector<estimation::NavState> states;
  states.swap(finalized_);
  return states;
}

void OdometryPipeline::CollectFinalized() {
  std::vector<estimation::NavState> finalized;
  estimator_->TakeFinalized(&finalized);
  // A trajectory holds places in the map only: the states of lost scans are left out, and a
  // relocalized scan is written (and mapped) where the relocalization put it.
  for (estimation::NavState& x : finalized) {
    // A pending scan older than this state was never finalized as a place in the map.
    while (!map_pending_.empty() && map_pending_.front().t_ns < x.t_ns) map_pending_.pop_front();
    if (untrusted_t_ns_.count(x.t_ns) != 0) continue;
    const auto replaced = replaced_.find(x.t_ns);
    if (replaced != replaced_.end()) x = replaced->second;
    if (!map_pending_.empty() && map_pending_.front().t_ns == x.t_ns) {
      const lie::SE3d T_map_lidar = x.T_map_lidar();
      map_.AddScan(Transformed(T_map_lidar, map_pending_.front().points_lidar),
                   T_map_lidar.translation().cast<float>());
      map_pending_.pop_front();
    }
    finalized_.push_back(std::move(x));
  }
  if (!finalized.empty()) {
    untrusted_t_ns_.erase(untrusted_t_ns_.begin(),
                          untrusted_t_ns_.upper_bound(finalized.back().t_ns));
    replaced_.erase(replaced_.begin(), replaced_.upper_bound(finalized.back().t_ns));
  }
}

bool OdometryPipeline::FollowStreamedPrior() {
  const estimation::NavState& x = estimator_->state();
  const Eigen::Vector3f position = x.p_map_imu.cast<float>();
  map_.BeginScan(position);
  if (!map_.prior_error().empty()) {
    Fail("prior map: " + map_.prior_error());
    return false;
  }
  if (supervisor_) {
    supervisor_->SetOnMap(map_.OnPriorMap(position), x.t_ns,
                          Eigen::Isometry3d(x.T_map_imu().Matrix()));
    map_.SetOnDemand(supervisor_->lost());  // a lost vehicle may be anywhere in the map
  }
  return true;
}

bool OdometryPipeline::ProcessScan(MeasurementGroup* group, ScanResult* result) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start_ms = CpuMs();
  const double process_cpu_start_ms = CpuMs(CLOCK_PROCESS_CPUTIME_ID);
  if (map_.streamed() && !FollowStreamedPrior()) return false;
  // After a gap in the data the scan is propagated only, not registered. A pose carried
  // through a gap by the IMU alone may be metres off; the update would pull it part of the
  // way to whatever fits there (and velocity and biases with it) at the cost of several
  // full iterations, while only the supervisor's fit near the propagated pose may confirm it.
  // After a gap without IMU the pose is unknown: the scan is not registered either, and the
  // supervisor searches for the place.
  const bool after_gap = AfterDataGapInMap(group->scan.end_t_ns);
  const bool blind_gap = RestartAfterBlindGap(group->scan.end_t_ns, group->imu);
  std::vector<int64_t> knots;
  for (const ImuSample& s : group->imu) {
    estimator_->AddImu(s);
    knots.push_back(s.t_ns);
  }
  PreparedScan scan;
  ScanSanitizeReport sanitized;
  const bool usable =
      preprocessor_.Prepare(std::move(group->scan), knots, *estimator_, &scan, &sanitized);
  counters_.points_dropped_sanitize += sanitized.total();
  if (!usable) {
    ++counters_.scans_too_small;
    return false;
  }
  result->raw_points = scan.cleaned.points.size();
  result->downsampled_points = scan.registration.points_lidar.size();
  // The dense copy is deskewed with the same sweep motion; it is registered after the update.
  const double dense_voxel_m = options_.output.dense_map_voxel_m;
  const PointCloud dense_lidar =
      dense_voxel_m > 0.0 ? preprocessor_.Deskewed(scan, dense_voxel_m) : PointCloud();
  result->deskew_ms = MsSince(start);

  const auto update_start = std::chrono::steady_clock::now();
  const bool searching = supervisor_ && supervisor_->searching();
  estimation::DeskewedScan nothing;
  nothing.t_ns = scan.registration.t_ns;
  // A search registers against its own scratch map, which takes every scan at once.
  estimator_->SetScansExtendMap(searching     ? false
                                : supervisor_ ? supervisor_->ScansExtendMap(scan.registration.t_ns)
                                              : options_.update_map);
  // Calibration is estimated against the prior map or SLAM's map, not the scratch map a
  // search builds from its own scans: there the extrinsic's tilt and the accelerometer bias
  // take up the vehicle's acceleration together, and the handover would carry both into the
  // map (docs/results.md, "Why #0 and #10 miss").
  estimator_->SetCalibrationHeld(searching);
  result->update = estimator_->Update(after_gap ? nothing : scan.registration,
                                      searching ? supervisor_->search_matcher() : matcher_);
  if (blind_gap) result->update.message = "not registered: the first scan after a gap without IMU";
  else if (after_gap) result->update.message = "not registered: the first scan after a gap in the data";
  result->update_ms = MsSince(update_start);
  ++counters_.scans_processed;
  if (!result->update.applied) ++counters_.scans_not_applied;
  if (result->update.degenerate) ++counters_.scans_degenerate;
  result->t_ns = estimator_->state().t_ns;
  // Every scan's interval counts, searching or not: a search's scans are not a gap after it.
  const double gap_s = scan_clock_.Tick(result->t_ns);
  result->state = estimator_->state();
  result->pose_covariance = estimator_->PoseCovariance();
  result->health = localization::EvaluateScanHealth(result->update, options_.localization);
  const auto sweep_imu = [&] {
    return SweepImu(scan.motion, scan.cleaned, estimator_->state().T_imu_lidar);
  };
  if (searching) {
    // No place in the map yet: the scan is registered in the search frame, its result is
    // provisional, and the supervisor tries to place the accumulated scans in the map.
    result->pose_status = PoseStatus::kProvisional;
    std::string why;
    const PointCloud map_points_search =
        result->update.applied
            ? Transformed(result->state.T_map_lidar(), scan.registration.points_lidar)
            : PointCloud();
    // The search's copy of the whole sweep is undistorted where the search accumulates its
    // scans: off the scan path when it searches in the background. It owns the dense returns,
    // which are not needed here after this.
    auto dense_sweep_imu = [cleaned = std::move(scan.cleaned), motion = scan.motion,
                            T_imu_lidar = result->state.T_imu_lidar] {
      return SweepImu(motion, cleaned, T_imu_lidar);
    };
    const auto step = supervisor_->Search(std::move(dense_sweep_imu), map_points_search, map_,
                                          estimator_.get(), &why);
    if (step == localization::LocalizationSupervisor::SearchStep::kGaveUp) Fail(why);
    // The search frame's states are not the map's: none is finalized into a trajectory.
    std::vector<estimation::NavState> search_frame_states;
    estimator_->TakeFinalized(&search_frame_states);
    if (step == localization::LocalizationSupervisor::SearchStep::kLocalized) {
      result->pose_status = PoseStatus::kValid;
      result->state = estimator_->state();
      result->pose_covariance = estimator_->PoseCovariance();
    }
    result->T_map_odom = supervisor_->T_map_odom();
  } else if (supervisor_) {
    if (gap_s > 0.0) {
      supervisor_->DataGap(result->t_ns, gap_s, blind_gap,
                           lie::ToIsometry(result->state.T_map_imu()));
    }
    // Health, loss and relocalization may replace the estimator's pose.
    if (supervisor_->Supervise(result->t_ns, result->health, result->state, sweep_imu, map_,
                               estimator_.get())) {
      result->state = estimator_->state();
      result->pose_covariance = estimator_->PoseCovariance();
      replaced_[result->t_ns] = result->state;
    }
    result->T_map_odom = supervisor_->T_map_odom();
    if (supervisor_->lost()) result->pose_status = PoseStatus::kLost;
    if (supervisor_->searching()) result->pose_status = PoseStatus::kProvisional;
  }
  if (result->pose_status != PoseStatus::kValid) untrusted_t_ns_.insert(result->t_ns);
  // The residuals have been read into the health; a run keeps every result, and a few
  // thousand floats per scan would make its memory grow with its length.
  std::vector<float>().swap(result->update.point_residuals_m);

  const auto map_start = std::chrono::steady_clock::now();
  if (result->pose_status != PoseStatus::kProvisional) UpdateMap(scan.registration, result);
  CollectFinalized();
  result->map_ms = MsSince(map_start);
  // Only a scan placed in the map joins the dense map: a lost or provisional one would smear it.
  if (result->update.applied && result->pose_status == PoseStatus::kValid) {
    result->registered_points_map = Transformed(result->state.T_map_lidar(), dense_lidar);
  }
  result->map_points = map_.Size();
  twist_.Fill(group->imu, *estimator_, result);
  result->total_ms = MsSince(start);
  result->cpu_ms = CpuMs() - cpu_start_ms;
  result->process_cpu_ms = CpuMs(CLOCK_PROCESS_CPUTIME_ID) - process_cpu_start_ms;
  return true;
}

void OdometryPipeline::UpdateMap(const estimation::DeskewedScan& scan, ScanResult* result) {
  const bool allowed = supervisor_
                           ? supervisor_->MapUpdateAllowed(result->t_ns, result->update.applied,
                                                           result->health, result->state)
                           : options_.update_map && (map_.Size() == 0 || result->update.applied);
  if (!allowed) return;
  // Added at its finalized state (CollectFinalized): at once with the filter, when the scan
  // leaves the smoother's window.
  map_pending_.push_back({result->t_ns, scan.points_lidar});
  result->map_updated = true;
}

}  // namespace hylo::odometry
