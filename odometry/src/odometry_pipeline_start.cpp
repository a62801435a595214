// How the pipeline starts: the static IMU initialisation, then either SLAM from the levelled
// IMU pose, or localization from the pose the ICP initializer accepts in the prior map.
//
// With an IMU the scans taken while it initialises are dropped (SLAM) or, with a prior map,
// accumulated for the ICP start until init_scans static scans are there or the vehicle moves.
// Without an IMU nothing says the vehicle is at rest: the first scan starts the run (SLAM at
// the identity, localization from the first scan alone) and is then processed as any other.
#include <cmath>
#include <stdexcept>

#include "hylo/common/check.h"
#include "hylo/localization/icp_initializer.h"
#include "hylo/odometry/odometry_pipeline.h"

namespace hylo::odometry {

void OdometryPipeline::SetPriorMap(const PointCloud& points_map) {
  HYLO_CHECK(status_ == Status::kInitializing && counters_.scans_processed == 0);
  HYLO_CHECK(!supervisor_, "the prior map is set before the initial guess");
  map_.SetPrior(points_map);
  global_search_ = std::make_unique<localization::GlobalSearch>(options_.localization, points_map);
}

void OdometryPipeline::SetStreamedPriorMap(std::shared_ptr<mapping::StreamedPrior> prior,
                                           const PointCloud& overview_points) {
  HYLO_CHECK(status_ == Status::kInitializing && counters_.scans_processed == 0);
  HYLO_CHECK(!supervisor_, "the prior map is set before the initial guess");
  map_.SetStreamedPrior(std::move(prior));
  global_search_ = std::make_unique<localization::GlobalSearch>(
      options_.localization, overview_points, "the tiled map has no overview to search");
}

void OdometryPipeline::SetInitialGuess(const std::optional<Eigen::Isometry3d>& T_map_imu_guess) {
  HYLO_CHECK(status_ == Status::kInitializing);
  supervisor_.reset();  // waits for a global attempt of the one it replaces
  if (!global_search_) {
    global_search_ = std::make_unique<localization::GlobalSearch>(
        options_.localization, PointCloud(), "no prior map was given (SetPriorMap)");
  }
  localization::LocalizationOptions localization = options_.localization;
  // A streamed prior changes under the scan thread: its global attempts run there.
  if (map_.streamed()) localization.search.background = false;
  supervisor_ = std::make_unique<localization::LocalizationSupervisor>(
      localization, options_.initial_uncertainty, T_map_imu_guess, global_search_.get(),
      options_.map, options_.planes);
}

void OdometryPipeline::RequestRelocalization(const Eigen::Isometry3d& T_map_imu_guess) {
  if (!supervisor_) {
    SetInitialGuess(T_map_imu_guess);
    return;
  }
  supervisor_->RequestRelocalization(T_map_imu_guess);
}

bool OdometryPipeline::RequestGlobalLocalization(std::string* why) {
  if (!supervisor_) {
    *why = "no prior map (SLAM): nothing to localize in";
    return false;
  }
  return supervisor_->RequestGlobalLocalization(why);
}

void OdometryPipeline::Fail(const std::string& why) {
  status_ = Status::kFailed;
  message_ = why;
}

bool OdometryPipeline::Start(const MeasurementGroup& group) {
  if (map_.prior_size() > 0 && !supervisor_) {
    Fail("a prior map was given without SetInitialGuess (std::nullopt: a global start)");
    return true;
  }
  if (!options_.imu.enabled) return StartWithoutImu(group);
  const bool imu_was_ready = imu_initializer_.status() == estimation::ImuInitializer::Status::kDone;
  if (!imu_was_ready) {
    const std::size_t used = FeedImuInitializer(group);
    if (imu_initializer_.status() == estimation::ImuInitializer::Status::kFailed) {
      Fail(imu_initializer_.message());
      return true;
    }
    if (imu_initializer_.status() == estimation::ImuInitializer::Status::kMoving) {
      StartMoving(group, {group.imu.begin() + (used - 1), group.imu.end()});
      return true;
    }
    if (!supervisor_) {
      // The scan that completed the initialisation started before it: dropped.
      if (imu_initializer_.status() == estimation::ImuInitializer::Status::kDone && used > 0) {
        StartSlam(imu_initializer_.state(), {group.imu.begin() + (used - 1), group.imu.end()});
      }
      return true;
    }
  }
  // Localization: static scans feed the ICP start; a scan in which the vehicle moves ends the
  // accumulation and is processed from the accepted pose.
  const bool imu_ready = imu_initializer_.status() == estimation::ImuInitializer::Status::kDone;
  if (!imu_ready || localization::ImuAtRest(group.imu, imu_initializer_.state(), options_.init,
                                            options_.imu.gravity_mps2)) {
    AddStaticScan(group);
  } else if (imu_was_ready) {
    StartLocalization(group);
    return status_ != Status::kRunning;
  }
  if (imu_ready && supervisor_->static_scans() >= options_.localization.init_scans) {
    StartLocalization(group);
  }
  return true;
}

bool OdometryPipeline::StartWithoutImu(const MeasurementGroup& group) {
  if (supervisor_) {
    AddStaticScan(group);
    StartLocalization(group);
    return status_ != Status::kRunning;
  }
  estimation::NavState x;
  x.t_ns = group.scan.t_ns;  // the first scan then registers at its own end time
  x.gravity_map = Eigen::Vector3d(0.0, 0.0, -options_.imu.gravity_mps2);
  StartSlam(x, {});
  return false;
}

std::size_t OdometryPipeline::FeedImuInitializer(const MeasurementGroup& group) {
  std::size_t used = 0;
  for (const ImuSample& s : group.imu) {
    ++used;
    if (imu_initializer_.Add(s) != estimation::ImuInitializer::Status::kCollecting) break;
  }
  return used;
}

void OdometryPipeline::StartSlam(const estimation::NavState& start,
                                 const std::vector<ImuSample>& imu_after) {
  estimation::NavState x = start;
  x.T_imu_lidar = options_.T_imu_lidar;
  estimator_->Initialize(x, options_.initial_uncertainty.SlamCovariance());
  for (const ImuSample& s : imu_after) estimator_->AddImu(s);
  status_ = Status::kRunning;
}

void OdometryPipeline::StartMoving(const MeasurementGroup& group,
                                   const std::vector<ImuSample>& imu_after) {
  estimation::NavState x = imu_initializer_.state();
  x.T_imu_lidar = options_.T_imu_lidar;
  const estimation::StateCovariance P = options_.initial_uncertainty.MovingCovariance(x);
  if (supervisor_) {
    // No place yet and no static scans to find one with: the vehicle searches while it
    // moves, from the scan that ended the initialisation.
    std::string why;
    if (!supervisor_->StartMoving(x, P, ScanInImu(group), imu_initializer_.message(),
                                  estimator_.get(), &why)) {
      Fail(why);
      return;
    }
  } else {
    estimator_->Initialize(x, P);
  }
  for (const ImuSample& s : imu_after) estimator_->AddImu(s);
  status_ = Status::kRunning;
}

PointCloud OdometryPipeline::ScanInImu(const MeasurementGroup& group) {
  LidarScan scan = group.scan;
  preprocessor_.Clean(&scan);
  PointCloud points_imu;
  points_imu.reserve(scan.points.size());
  for (const ScanPoint& p : scan.points) {
    points_imu.push_back((options_.T_imu_lidar * p.position_lidar.cast<double>()).cast<float>());
  }
  return points_imu;
}

void OdometryPipeline::AddStaticScan(const MeasurementGroup& group) {
  supervisor_->AddStaticScan(ScanInImu(group), group.imu.empty() ? 0 : group.imu.back().t_ns);
}

void OdometryPipeline::StartLocalization(const MeasurementGroup& group) {
  estimation::NavState x;
  if (options_.imu.enabled) {
    x = imu_initializer_.state();
  } else {
    x.t_ns = group.scan.t_ns;
    x.gravity_map = Eigen::Vector3d(0.0, 0.0, -options_.imu.gravity_mps2);
  }
  x.T_imu_lidar = options_.T_imu_lidar;
  std::string why;
  // The start may look anywhere in a tiled prior (global hypotheses): tiles on demand.
  // Searching while moving runs the estimator too, in its own frame (status() says
  // kInitializing until a pose is accepted).
  map_.SetOnDemand(true);
  const bool started = supervisor_->Start(x, options_.imu.enabled, map_, estimator_.get(), &why);
  map_.SetOnDemand(false);
  if (!map_.prior_error().empty()) {
    Fail("prior map: " + map_.prior_error());
  } else if (started || supervisor_->searching()) {
    status_ = Status::kRunning;
  } else {
    Fail(why);
  }
}

}  // namespace hylo::odometry
