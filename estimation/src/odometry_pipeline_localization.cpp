// Localization in a prior map: the ICP start, hybrid map updates, health and relocalization
// (localization.h). Kept apart from the odometry loop, which only calls these hooks.

#include <cmath>
#include <sstream>

#include "hylo/common/check.h"
#include "hylo/common/time.h"
#include "hylo/estimation/ieskf.h"
#include "hylo/estimation/odometry_pipeline.h"
#include "hylo/estimation/undistortion.h"

namespace hylo::estimation {
namespace {

// The covariance a pose from the ICP initializer starts with: the filter's initial settings,
// but the position is known only to the initializer's accuracy (a few cm), not by definition
// as in SLAM.
StateCovariance LocalizationCovariance(const IeskfOptions& options) {
  StateCovariance P = Ieskf::InitialCovariance(options);
  constexpr double kIcpPositionSigmaM = 0.05;
  P.block<3, 3>(state_index::kPosition, state_index::kPosition) =
      kIcpPositionSigmaM * kIcpPositionSigmaM * Eigen::Matrix3d::Identity();
  return P;
}

// True when the group's IMU says the vehicle is still at rest, judged with the static
// initialisation's thresholds against its gyro bias and gravity magnitude.
bool GroupAtRest(const MeasurementGroup& group, const NavState& initial,
                 const ImuInitializerOptions& init, double gravity_mps2) {
  if (group.imu.empty()) return false;
  Eigen::Vector3d gyro_mean = Eigen::Vector3d::Zero();
  double accel_norm_mean = 0.0;
  for (const ImuSample& s : group.imu) {
    gyro_mean += s.gyro_imu;
    accel_norm_mean += s.accel_imu.norm();
  }
  const double n = static_cast<double>(group.imu.size());
  gyro_mean /= n;
  accel_norm_mean /= n;
  return (gyro_mean - initial.gyro_bias).norm() < init.max_gyro_mean_radps &&
         std::abs(accel_norm_mean - gravity_mps2) < init.gravity_tolerance_mps2;
}

double YawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

lie::SE3d ToSE3(const Eigen::Isometry3d& T) {
  return lie::SE3d(lie::SO3d::FromMatrix(T.rotation()), T.translation());
}

}  // namespace

void OdometryPipeline::SetPriorMap(const registration::PointCloud& points_map) {
  HYLO_CHECK(status_ == Status::kInitializing && counters_.scans_processed == 0);
  map_.SetPrior(points_map);
  have_prior_ = !points_map.empty();
}

void OdometryPipeline::SetInitialGuess(const Eigen::Isometry3d& T_map_imu_guess) {
  HYLO_CHECK(status_ == Status::kInitializing);
  T_map_imu_guess_ = T_map_imu_guess;
  localizing_ = true;
}

void OdometryPipeline::RequestRelocalization(const Eigen::Isometry3d& T_map_imu_guess) {
  if (status_ == Status::kInitializing) {
    SetInitialGuess(T_map_imu_guess);
    return;
  }
  has_relocalize_request_ = true;
  relocalize_guess_ = T_map_imu_guess;
}

bool OdometryPipeline::AccumulateStaticScan(const MeasurementGroup& group) {
  const bool imu_done = initializer_.status() == ImuInitializer::Status::kDone;
  if (options_.estimator.use_imu && imu_done &&
      !GroupAtRest(group, initializer_.state(), options_.init, options_.gravity_mps2)) {
    return false;
  }
  LidarScan scan = group.scan;
  const PreprocessOptions& pre = options_.preprocess;
  SanitizeScan(&scan, static_cast<float>(pre.min_range_m), static_cast<float>(pre.max_range_m),
               SecondsToNanos(pre.max_point_offset_s));
  const lie::SE3d& T_imu_lidar = options_.T_imu_lidar;
  for (const registration::ScanPoint& p : scan.points) {
    static_cloud_imu_.push_back((T_imu_lidar * p.position_lidar.cast<double>()).cast<float>());
  }
  if (!group.imu.empty()) static_end_t_ns_ = group.imu.back().t_ns;
  ++static_scans_;
  ++counters_.scans_initializer;
  return true;
}

void OdometryPipeline::StartFromIcp(const MeasurementGroup& group) {
  Eigen::Isometry3d guess = T_map_imu_guess_;
  NavState x;
  if (options_.estimator.use_imu) {
    // Roll and pitch from gravity, yaw and position from the user's guess.
    x = initializer_.state();
    const Eigen::Vector3d up_imu = x.R_map_imu.Matrix().transpose() * Eigen::Vector3d::UnitZ();
    guess = registration::GuessFromGravity(T_map_imu_guess_.translation(),
                                           YawOf(T_map_imu_guess_.rotation()), up_imu);
    x.t_ns = static_end_t_ns_;
  } else {
    x.t_ns = group.scan.t_ns;
    x.gravity_map = Eigen::Vector3d(0.0, 0.0, -options_.gravity_mps2);
  }
  const registration::IcpInitializerResult icp =
      icp_initializer_.Initialize(static_cloud_imu_, map_, guess);
  registration::PointCloud().swap(static_cloud_imu_);
  if (!icp.accepted) {
    status_ = Status::kFailed;
    message_ = "ICP initializer rejected the start (" + std::to_string(static_scans_) +
               " static scans): " + icp.message;
    AddEvent(LocalizationEvent::Kind::kInitializationFailed, x.t_ns, icp.message, &icp);
    return;
  }
  const lie::SE3d T_map_imu = ToSE3(icp.T_map_imu);
  x.R_map_imu = T_map_imu.so3();
  x.p_map_imu = T_map_imu.translation();
  x.v_map_imu.setZero();
  x.T_imu_lidar = options_.T_imu_lidar;
  estimator_->Initialize(x, LocalizationCovariance(options_.estimator.ieskf));
  localization_start_ns_ = x.t_ns;
  status_ = Status::kRunning;
  AddEvent(LocalizationEvent::Kind::kInitialized, x.t_ns, icp.message, &icp);
}

bool OdometryPipeline::MapUpdateAllowed(int64_t t_ns, const ScanResult& result) {
  if (!localizing_) return options_.update_map && (map_.Size() == 0 || result.update.applied);
  const double after_s = options_.localization.update_after_s;
  if (after_s < 0.0 || NanosToSeconds(t_ns - localization_start_ns_) < after_s) return false;
  if (!hybrid_started_) {
    hybrid_started_ = true;
    AddEvent(LocalizationEvent::Kind::kHybridStarted, t_ns,
             "registered scans are added to the map from now on");
  }
  // Only scans that fit the map extend it: a scan registered while lost would corrupt it.
  return result.update.applied && result.health.good && status_ == Status::kRunning;
}

void OdometryPipeline::CheckHealth(const LidarScan& scan, const DeskewedScan& scan_downsampled,
                                   const std::vector<int64_t>& imu_knots, ScanResult* result) {
  const LocalizationOptions& lo = options_.localization;
  const lie::SE3d T_map_lidar = estimator_->state().T_map_lidar();
  registration::PointCloud points_map;
  points_map.reserve(scan_downsampled.points_lidar.size());
  for (const Eigen::Vector3f& p : scan_downsampled.points_lidar) {
    points_map.push_back((T_map_lidar * p.cast<double>()).cast<float>());
  }
  result->health = EvaluateScanHealth(points_map, matcher_, result->update.num_matches, lo);
  if (!result->health.good) ++counters_.scans_bad_health;
  bad_scans_in_row_ = result->health.good ? 0 : bad_scans_in_row_ + 1;
  if (status_ == Status::kLost && result->health.good) status_ = Status::kRunning;
  if (status_ == Status::kRunning && bad_scans_in_row_ >= lo.lost_after_scans) {
    status_ = Status::kLost;
    scans_until_retry_ = 0;
    std::ostringstream os;
    os << bad_scans_in_row_ << " bad scans in a row (inlier ratio "
       << result->health.inlier_ratio << ", " << result->health.num_matches << " matches)";
    AddEvent(LocalizationEvent::Kind::kLost, scan_downsampled.t_ns, os.str());
  }
  const lie::SE3d T_map_imu = estimator_->state().T_map_imu();
  bool relocalized = false;
  if (has_relocalize_request_) {
    has_relocalize_request_ = false;
    relocalized = Relocalize(scan, imu_knots, relocalize_guess_);
  } else if (status_ == Status::kLost && scans_until_retry_-- <= 0) {
    Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
    guess.linear() = T_map_imu.so3().Matrix();
    guess.translation() = T_map_imu.translation();
    relocalized = Relocalize(scan, imu_knots, guess);
    if (!relocalized) scans_until_retry_ = lo.relocalize_retry_scans;
  }
  if (!relocalized) return;
  // The initializer's point-to-point pose is refined by the back-end's usual point-to-plane
  // update on the same scan, and the scan's health is taken again at the refined pose.
  result->update = estimator_->Update(scan_downsampled, matcher_);
  const lie::SE3d T_map_lidar_refined = estimator_->state().T_map_lidar();
  for (std::size_t i = 0; i < points_map.size(); ++i) {
    points_map[i] =
        (T_map_lidar_refined * scan_downsampled.points_lidar[i].cast<double>()).cast<float>();
  }
  result->health = EvaluateScanHealth(points_map, matcher_, result->update.num_matches, lo);
}

bool OdometryPipeline::Relocalize(const LidarScan& scan, const std::vector<int64_t>& imu_knots,
                                  const Eigen::Isometry3d& T_map_imu_guess) {
  const NavState before = estimator_->state();
  // The whole scan (not the 0.5 m voxels of the update) at the scan end, in the IMU frame.
  const registration::PointCloud points_lidar =
      options_.estimator.use_imu && options_.preprocess.deskew
          ? Undistort(scan, *estimator_, imu_knots)
          : PointsOf(scan);
  registration::PointCloud points_imu;
  points_imu.reserve(points_lidar.size());
  for (const Eigen::Vector3f& p : points_lidar) {
    points_imu.push_back((before.T_imu_lidar * p.cast<double>()).cast<float>());
  }
  ++counters_.scans_initializer;
  const registration::IcpInitializerResult icp =
      icp_initializer_.Initialize(points_imu, map_, T_map_imu_guess);
  if (!icp.accepted) {
    AddEvent(LocalizationEvent::Kind::kRelocalizationFailed, before.t_ns, icp.message, &icp);
    return false;
  }
  NavState x = before;
  const lie::SE3d T_map_imu = ToSE3(icp.T_map_imu);
  x.R_map_imu = T_map_imu.so3();
  x.p_map_imu = T_map_imu.translation();
  x.v_map_imu = x.R_map_imu * (before.R_map_imu.Inverse() * before.v_map_imu);  // body velocity
  estimator_->Initialize(x, LocalizationCovariance(options_.estimator.ieskf));
  // REP-105: odom→imu stays continuous, the jump goes into map→odom.
  const lie::SE3d T_odom_imu_before = T_map_odom_.Inverse() * before.T_map_imu();
  T_map_odom_ = x.T_map_imu() * T_odom_imu_before.Inverse();
  bad_scans_in_row_ = 0;
  status_ = Status::kRunning;
  AddEvent(LocalizationEvent::Kind::kRelocalized, x.t_ns, icp.message, &icp);
  return true;
}

void OdometryPipeline::AddEvent(LocalizationEvent::Kind kind, int64_t t_ns,
                                const std::string& message,
                                const registration::IcpInitializerResult* icp) {
  LocalizationEvent event;
  event.kind = kind;
  event.t_ns = t_ns;
  const lie::SE3d T_map_imu =
      estimator_->initialized() ? estimator_->state().T_map_imu() : lie::SE3d();
  event.T_map_imu.linear() = T_map_imu.so3().Matrix();
  event.T_map_imu.translation() = T_map_imu.translation();
  if (icp != nullptr) {
    event.fitness_m2 = icp->accepted ? icp->fitness_score_m2 : icp->best_fitness_score_m2;
    event.inlier_ratio = icp->accepted ? icp->inlier_ratio : icp->best_inlier_ratio;
  }
  event.message = message;
  events_.push_back(event);
}

}  // namespace hylo::estimation
