// Searching while moving (moving_search.h): the scratch map, the accumulated cloud and when to
// try the global localizer again.
#include "hylo/localization/moving_search.h"

#include <optional>
#include <sstream>
#include <utility>

#include "hylo/common/transformed_cloud.h"

namespace hylo::localization {
namespace {

// Each waiting job holds a dense sweep (megabytes on a 128-beam head): a computer that cannot
// keep up with the accumulation makes the scan path wait after about two seconds of sweeps
// rather than memory grow.
constexpr std::size_t kMaxSweepsWaiting = 20;
// Below the scan thread, which it would otherwise take CPU from on a small computer (on two
// cores, with an attempt running, searching scans lost up to 12 ms of a ~15 ms scan to it);
// above the attempts (background_search.cpp), which wait for its clouds.
constexpr int kAccumulationNicenessBelowScanThread = 5;

}  // namespace

MovingSearch::MovingSearch(const MovingSearchOptions& options,
                           const mapping::MapManagerOptions& map,
                           const registration::PlaneMatcherOptions& planes, double keep_radius_m,
                           int recent_scans, bool accumulate_on_worker)
    : options_(options),
      keep_radius_m_(keep_radius_m),
      map_(map),
      matcher_(std::make_unique<registration::PlaneMatcher>(map_, planes)),
      recent_scans_(recent_scans),
      cloud_search_(static_cast<float>(options.voxel_m)),
      accumulation_(accumulate_on_worker, kMaxSweepsWaiting, kAccumulationNicenessBelowScanThread) {
}

void MovingSearch::Begin(const PointCloud& points_imu, const Eigen::Isometry3d& T_search_imu) {
  const PointCloud thinned =
      registration::UniformSample(points_imu, static_cast<float>(options_.voxel_m));
  const PointCloud points_search = Transformed(T_search_imu, thinned);
  map_.AddScan(points_search, T_search_imu.translation().cast<float>());
  cloud_search_.Add(points_search);
  last_position_ = T_search_imu.translation();
  attempt_position_ = last_position_;
}

bool MovingSearch::Add(std::function<PointCloud()> sweep_imu, const PointCloud& map_points_search,
                       const Eigen::Isometry3d& T_search_imu, int first_attempt_scans) {
  // The scratch map is what the next scan registers against: it grows here. The accumulated
  // cloud is read by attempts alone, seconds apart: it grows where it costs the scan path
  // nothing.
  if (!map_points_search.empty()) {
    map_.AddScan(map_points_search, T_search_imu.translation().cast<float>());
  }
  accumulation_.Post([this, sweep_imu = std::move(sweep_imu), T_search_imu] {
    const PointCloud thinned =
        registration::UniformSample(sweep_imu(), static_cast<float>(options_.voxel_m));
    PointCloud thinned_search = Transformed(T_search_imu, thinned);
    cloud_search_.Add(thinned_search);
    recent_search_.push_back(std::move(thinned_search));
    while (static_cast<int>(recent_search_.size()) > recent_scans_) recent_search_.pop_front();
  });
  ++scans_;
  distance_m_ += (T_search_imu.translation() - last_position_).norm();
  last_position_ = T_search_imu.translation();
  if (attempts_ == 0 && first_attempt_scans > 0 && scans_ >= first_attempt_scans) return true;
  return (last_position_ - attempt_position_).norm() >= options_.retry_m;
}

std::shared_future<AttemptClouds> MovingSearch::TakeAttemptClouds(
    const Eigen::Isometry3d& T_search_imu) {
  ++attempts_;
  attempt_position_ = T_search_imu.translation();
  return accumulation_.Ask([this, T_search_imu] {
    const Eigen::Isometry3d T_imu_search = T_search_imu.inverse();
    AttemptClouds clouds;
    clouds.accumulated.points = KeepNear(T_search_imu.translation().cast<float>());
    clouds.accumulated.T_attempt_from = T_imu_search;
    for (const PointCloud& sweep : recent_search_) {
      clouds.recent.points.insert(clouds.recent.points.end(), sweep.begin(), sweep.end());
    }
    clouds.recent.T_attempt_from = T_imu_search;
    return clouds;
  });
}

PointCloud MovingSearch::KeepNear(const Eigen::Vector3f& center_search) {
  const float radius_sq = static_cast<float>(keep_radius_m_ * keep_radius_m_);
  PointCloud kept;
  for (const Eigen::Vector3f& p : cloud_search_.points()) {
    if ((p - center_search).squaredNorm() <= radius_sq) kept.push_back(p);
  }
  if (kept.size() < cloud_search_.points().size()) {
    registration::UniformSampler cropped(static_cast<float>(options_.voxel_m));
    cropped.Add(kept);
    cloud_search_ = std::move(cropped);
  }
  return kept;
}

bool MovingSearch::GaveUp() const {
  return options_.max_distance_m > 0.0 && distance_m_ > options_.max_distance_m;
}

}  // namespace hylo::localization
