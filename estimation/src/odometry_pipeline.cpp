#include "hylo/estimation/odometry_pipeline.h"

#include <time.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <vector>

#include "hylo/common/check.h"
#include "hylo/common/time.h"
#include "hylo/estimation/ieskf.h"
#include "hylo/estimation/undistortion.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::estimation {
namespace {

MeasurementQueueOptions QueueOptions(const OdometryPipelineOptions& o) {
  MeasurementQueueOptions q = o.queue;
  q.use_imu = o.estimator.use_imu;
  return q;
}

// Every `stride`-th return of each ring, in the driver's order (a ring's returns arrive in
// time order, so this thins each scan line evenly along the sweep).
std::vector<std::size_t> StridedIndices(const LidarScan& scan, int stride) {
  std::vector<std::size_t> kept;
  kept.reserve(scan.points.size() / static_cast<std::size_t>(stride) + 1);
  std::vector<int> seen_in_ring;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const uint16_t ring = scan.points[i].ring;
    if (ring >= seen_in_ring.size()) seen_in_ring.resize(ring + 1u, 0);
    if (seen_in_ring[ring]++ % stride == 0) kept.push_back(i);
  }
  return kept;
}

// The scan's points kept by the ring stride, then by uniform sampling of their raw positions
// (times and rings kept).
LidarScan DownsampleScan(const LidarScan& scan, double voxel_m, int stride = 1) {
  LidarScan kept;
  kept.t_ns = scan.t_ns;
  kept.end_t_ns = scan.end_t_ns;
  kept.frame_id = scan.frame_id;
  std::vector<std::size_t> candidates;
  registration::PointCloud positions;
  if (stride > 1) {
    candidates = StridedIndices(scan, stride);
    positions.reserve(candidates.size());
    for (std::size_t i : candidates) positions.push_back(scan.points[i].position_lidar);
  } else {
    positions = PointsOf(scan);
  }
  const std::vector<std::size_t> sampled =
      registration::UniformSampleIndices(positions, static_cast<float>(voxel_m));
  kept.points.reserve(sampled.size());
  for (std::size_t j : sampled) kept.points.push_back(scan.points[stride > 1 ? candidates[j] : j]);
  return kept;
}

double CpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

double MsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

template <class S>
bool SectionValid(const S& section, const char* name, std::string* why) {
  std::string inner;
  if (section.IsValid(&inner)) return true;
  if (why != nullptr) *why = std::string(name) + "." + inner;
  return false;
}

}  // namespace

bool PreprocessOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(min_range_m >= 0.0) || !std::isfinite(min_range_m)) {
    os << "min_range_m = " << min_range_m << ": must be finite and >= 0";
  } else if (!(max_range_m > min_range_m) || !std::isfinite(max_range_m)) {
    os << "max_range_m = " << max_range_m << ": must be finite and > min_range_m";
  } else if (!(max_point_offset_s > 0.0) || !std::isfinite(max_point_offset_s)) {
    os << "max_point_offset_s = " << max_point_offset_s << ": must be finite and > 0";
  } else if (!(scan_voxel_m >= 0.0) || !std::isfinite(scan_voxel_m)) {
    os << "scan_voxel_m = " << scan_voxel_m << ": must be finite and >= 0";
  } else if (point_stride < 1) {
    os << "point_stride = " << point_stride << ": must be >= 1 (1 = keep every return)";
  } else if (min_points < 1) {
    os << "min_points = " << min_points << ": must be >= 1";
  } else {
    return true;
  }
  if (why != nullptr) *why = os.str();
  return false;
}

bool OdometryPipelineOptions::IsValid(std::string* why) const {
  if (!(gravity_mps2 > 9.0 && gravity_mps2 < 10.5)) {
    if (why != nullptr) {
      *why = "gravity_mps2 = " + std::to_string(gravity_mps2) + ": must be in (9, 10.5)";
    }
    return false;
  }
  if (!(registered_scan_voxel_m >= 0.0 && std::isfinite(registered_scan_voxel_m))) {
    if (why != nullptr) {
      *why = "registered_scan_voxel_m = " + std::to_string(registered_scan_voxel_m) +
             ": must be finite and >= 0";
    }
    return false;
  }
  return SectionValid(estimator, "estimator", why) && SectionValid(init, "init", why) &&
         SectionValid(queue, "queue", why) && SectionValid(preprocess, "preprocess", why) &&
         SectionValid(planes, "planes", why) && SectionValid(map, "map", why) &&
         SectionValid(localization, "localization", why);
}

OdometryPipeline::OdometryPipeline(const OdometryPipelineOptions& options)
    : options_(options),
      queue_(QueueOptions(options)),
      initializer_(options.init, options.gravity_mps2),
      estimator_(Estimator::Create(options.estimator)),
      map_(options.map),
      matcher_(map_, options.planes),
      icp_initializer_(options.localization.icp) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("invalid options: " + why);
}

PipelineCounters OdometryPipeline::counters() const {
  PipelineCounters c = counters_;
  c.queue = queue_.counters();
  return c;
}

bool OdometryPipeline::Initialize(const MeasurementGroup& group) {
  if (have_prior_ && !localizing_) {
    status_ = Status::kFailed;
    message_ = "a prior map was given without an initial guess (SetInitialGuess)";
    return true;
  }
  if (!options_.estimator.use_imu) {
    if (localizing_) {
      // Without an IMU nothing says the vehicle is at rest: the first scan alone is
      // registered, and then processed like every other scan from the accepted pose.
      AccumulateStaticScan(group);
      StartFromIcp(group);
      return status_ != Status::kRunning;
    }
    NavState x;
    x.t_ns = group.scan.t_ns;  // the first scan then registers at its own end time
    x.gravity_map = Eigen::Vector3d(0.0, 0.0, -options_.gravity_mps2);
    x.T_imu_lidar = options_.T_imu_lidar;
    estimator_->Initialize(x, Ieskf::InitialCovariance(options_.estimator.ieskf));
    status_ = Status::kRunning;
    return false;
  }
  if (initializer_.status() == ImuInitializer::Status::kDone) {
    // Localization only: the IMU is initialised and more static scans are wanted. A group in
    // which the vehicle moves ends the accumulation and is processed from the ICP pose.
    if (AccumulateStaticScan(group)) {
      if (static_scans_ >= options_.localization.init_scans) StartFromIcp(group);
      return true;
    }
    StartFromIcp(group);
    return status_ != Status::kRunning;
  }
  std::size_t used = 0;
  for (const ImuSample& s : group.imu) {
    ++used;
    if (initializer_.Add(s) != ImuInitializer::Status::kCollecting) break;
  }
  if (initializer_.status() == ImuInitializer::Status::kFailed) {
    status_ = Status::kFailed;
    message_ = initializer_.message();
    return true;
  }
  if (localizing_) {
    // The scans taken while the IMU proves the vehicle is at rest feed the ICP initializer.
    AccumulateStaticScan(group);
    if (initializer_.status() == ImuInitializer::Status::kDone &&
        static_scans_ >= options_.localization.init_scans) {
      StartFromIcp(group);
    }
    return true;
  }
  if (initializer_.status() != ImuInitializer::Status::kDone) return true;
  NavState x = initializer_.state();
  x.T_imu_lidar = options_.T_imu_lidar;
  estimator_->Initialize(x, Ieskf::InitialCovariance(options_.estimator.ieskf));
  for (std::size_t i = used - 1; i < group.imu.size(); ++i) estimator_->AddImu(group.imu[i]);
  status_ = Status::kRunning;
  // The scan that completed the initialisation started before it: dropped.
  return true;
}

void OdometryPipeline::Process(std::vector<ScanResult>* results, bool flush) {
  MeasurementGroup group;
  while (status_ != Status::kFailed && queue_.Pop(&group, flush)) {
    if (status_ == Status::kInitializing) {
      const std::size_t before = counters_.scans_initializer;
      if (Initialize(group)) {
        if (counters_.scans_initializer == before) ++counters_.scans_before_init;
        continue;
      }
    }
    ScanResult result;
    if (ProcessScan(&group, &result)) results->push_back(std::move(result));
  }
  // A log that ends while the initializer still waits for static scans: register what there
  // is rather than end without a pose.
  if (flush && status_ == Status::kInitializing && localizing_ && static_scans_ > 0 &&
      initializer_.status() == ImuInitializer::Status::kDone) {
    StartFromIcp(MeasurementGroup());
  }
}

bool OdometryPipeline::ProcessScan(MeasurementGroup* group, ScanResult* result) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start_ms = CpuMs();
  std::vector<int64_t> knots;
  for (const ImuSample& s : group->imu) {
    estimator_->AddImu(s);
    knots.push_back(s.t_ns);
  }
  LidarScan& scan = group->scan;
  const PreprocessOptions& pre = options_.preprocess;
  const ScanSanitizeReport report = SanitizeScan(&scan, static_cast<float>(pre.min_range_m),
                                                 static_cast<float>(pre.max_range_m),
                                                 SecondsToNanos(pre.max_point_offset_s));
  counters_.points_dropped_sanitize += report.dropped_non_finite + report.dropped_out_of_range +
                                       report.dropped_bad_time;
  if (static_cast<int>(scan.points.size()) < pre.min_points) {
    ++counters_.scans_too_small;
    return false;
  }
  result->raw_points = scan.points.size();
  // Downsample first, then undistort only the kept points: the voxel (0.5 m) is much larger
  // than the motion within one sweep, and undistortion is the per-point cost.
  LidarScan kept = DownsampleScan(scan, pre.scan_voxel_m, pre.point_stride);
  DeskewedScan ds;
  ds.t_ns = scan.end_t_ns;
  ds.points_lidar =
      options_.estimator.use_imu && pre.deskew ? Undistort(kept, *estimator_, knots)
                                               : PointsOf(kept);
  result->downsampled_points = ds.points_lidar.size();
  // The dense copy is deskewed with the same prediction; it is registered after the update.
  registration::PointCloud dense_lidar;
  if (options_.registered_scan_voxel_m > 0.0) {
    const LidarScan dense = DownsampleScan(scan, options_.registered_scan_voxel_m);
    dense_lidar = options_.estimator.use_imu && pre.deskew ? Undistort(dense, *estimator_, knots)
                                                           : PointsOf(dense);
  }
  result->deskew_ms = MsSince(start);

  const auto update_start = std::chrono::steady_clock::now();
  result->update = estimator_->Update(ds, matcher_);
  result->update_ms = MsSince(update_start);
  ++counters_.scans_processed;
  if (!result->update.applied) ++counters_.scans_not_applied;
  if (result->update.degenerate) ++counters_.scans_degenerate;
  // Health, loss and relocalization may replace the estimator's pose.
  if (localizing_) CheckHealth(scan, ds, knots, result);

  const auto map_start = std::chrono::steady_clock::now();
  const NavState& x = estimator_->state();
  const lie::SE3d T_map_lidar = x.T_map_lidar();
  if (MapUpdateAllowed(x.t_ns, *result)) {
    registration::PointCloud points_map;
    points_map.reserve(ds.points_lidar.size());
    for (const Eigen::Vector3f& p : ds.points_lidar) {
      points_map.push_back((T_map_lidar * p.cast<double>()).cast<float>());
    }
    map_.AddScan(points_map, T_map_lidar.translation().cast<float>());
    result->map_updated = true;
  }
  result->map_ms = MsSince(map_start);
  if (result->update.applied) {
    result->registered_points_map.reserve(dense_lidar.size());
    for (const Eigen::Vector3f& p : dense_lidar) {
      result->registered_points_map.push_back((T_map_lidar * p.cast<double>()).cast<float>());
    }
  }
  result->map_points = map_.Size();
  result->t_ns = x.t_ns;
  result->state = x;
  result->pose_covariance = estimator_->PoseCovariance();
  result->T_map_odom = T_map_odom_;
  FillTwist(*group, result);
  result->total_ms = MsSince(start);
  result->cpu_ms = CpuMs() - cpu_start_ms;
  return true;
}

void OdometryPipeline::FillTwist(const MeasurementGroup& group, ScanResult* result) {
  const NavState& x = result->state;
  const Eigen::Matrix3d R_imu_map = x.R_map_imu.Matrix().transpose();
  const StateCovariance P = estimator_->Covariance();
  using state_index::kGyroBias;
  using state_index::kVelocity;
  result->linear_velocity_imu = R_imu_map * x.v_map_imu;
  result->twist_covariance.setZero();
  result->twist_covariance.topLeftCorner<3, 3>() =
      R_imu_map * P.block<3, 3>(kVelocity, kVelocity) * R_imu_map.transpose();
  if (options_.estimator.use_imu) {
    if (!group.imu.empty()) last_gyro_imu_ = group.imu.back().gyro_imu;
    if (group.imu.size() >= 2) {
      imu_period_s_ = NanosToSeconds(group.imu.back().t_ns - group.imu.front().t_ns) /
                      static_cast<double>(group.imu.size() - 1);
    }
    result->angular_velocity_imu = last_gyro_imu_ - x.gyro_bias;
    // One sample's white noise (the continuous density over the sample period) plus the bias.
    const double density = options_.estimator.imu_noise.gyro_noise_density;
    result->twist_covariance.bottomRightCorner<3, 3>() =
        P.block<3, 3>(kGyroBias, kGyroBias) +
        density * density / std::max(imu_period_s_, 1e-4) * Eigen::Matrix3d::Identity();
  } else if (have_previous_result_ && x.t_ns > previous_state_.t_ns) {
    // No IMU: the mean rate between the last two poses, with the variance of that difference.
    const double dt = NanosToSeconds(x.t_ns - previous_state_.t_ns);
    result->angular_velocity_imu =
        (previous_state_.R_map_imu.Inverse() * x.R_map_imu).Log() / dt;
    result->twist_covariance.bottomRightCorner<3, 3>() =
        (previous_pose_covariance_.bottomRightCorner<3, 3>() +
         result->pose_covariance.bottomRightCorner<3, 3>()) / (dt * dt);
  }
  have_previous_result_ = true;
  previous_state_ = x;
  previous_pose_covariance_ = result->pose_covariance;
}

}  // namespace hylo::estimation
