// Searching while moving (moving_search.h): the scratch map, the accumulated cloud and when to
// try the global localizer again.
#include <optional>
#include <sstream>
#include <utility>

#include "hylo/localization/moving_search.h"

namespace hylo::localization {
namespace {

PointCloud Transformed(const Eigen::Isometry3d& T_to_from, const PointCloud& points_from) {
  PointCloud points_to;
  points_to.reserve(points_from.size());
  for (const Eigen::Vector3f& p : points_from) {
    points_to.push_back((T_to_from * p.cast<double>()).cast<float>());
  }
  return points_to;
}

}  // namespace

MovingSearch::MovingSearch(const MovingSearchOptions& options,
                           const mapping::MapManagerOptions& map,
                           const registration::PlaneMatcherOptions& planes, double keep_radius_m,
                           int recent_scans)
    : options_(options),
      keep_radius_m_(keep_radius_m),
      map_(map),
      matcher_(std::make_unique<registration::PlaneMatcher>(map_, planes)),
      cloud_search_(static_cast<float>(options.voxel_m)),
      recent_scans_(recent_scans) {}

void MovingSearch::Begin(const PointCloud& points_imu, const Eigen::Isometry3d& T_search_imu) {
  const PointCloud thinned =
      registration::UniformSample(points_imu, static_cast<float>(options_.voxel_m));
  const PointCloud points_search = Transformed(T_search_imu, thinned);
  map_.AddScan(points_search, T_search_imu.translation().cast<float>());
  cloud_search_.Add(points_search);
  last_position_ = T_search_imu.translation();
  attempt_position_ = last_position_;
}

bool MovingSearch::Add(const PointCloud& sweep_imu, const PointCloud& map_points_search,
                       const Eigen::Isometry3d& T_search_imu, int first_attempt_scans) {
  const PointCloud thinned =
      registration::UniformSample(sweep_imu, static_cast<float>(options_.voxel_m));
  if (!map_points_search.empty()) {
    map_.AddScan(map_points_search, T_search_imu.translation().cast<float>());
  }
  PointCloud thinned_search = Transformed(T_search_imu, thinned);
  cloud_search_.Add(thinned_search);
  recent_search_.push_back(std::move(thinned_search));
  while (static_cast<int>(recent_search_.size()) > recent_scans_) recent_search_.pop_front();
  ++scans_;
  distance_m_ += (T_search_imu.translation() - last_position_).norm();
  last_position_ = T_search_imu.translation();
  if (attempts_ == 0 && first_attempt_scans > 0 && scans_ >= first_attempt_scans) return true;
  return (last_position_ - attempt_position_).norm() >= options_.retry_m;
}

PointCloud MovingSearch::TakeAttemptCloud(const Eigen::Isometry3d& T_search_imu) {
  ++attempts_;
  attempt_position_ = T_search_imu.translation();
  const Eigen::Vector3f center = T_search_imu.translation().cast<float>();
  const float radius_sq = static_cast<float>(keep_radius_m_ * keep_radius_m_);
  PointCloud kept;
  for (const Eigen::Vector3f& p : cloud_search_.points()) {
    if ((p - center).squaredNorm() <= radius_sq) kept.push_back(p);
  }
  if (kept.size() < cloud_search_.points().size()) {
    registration::UniformSampler cropped(static_cast<float>(options_.voxel_m));
    cropped.Add(kept);
    cloud_search_ = std::move(cropped);
  }
  return Transformed(T_search_imu.inverse(), kept);
}

PointCloud MovingSearch::RecentInImu(const Eigen::Isometry3d& T_search_imu) const {
  const Eigen::Isometry3d T_imu_search = T_search_imu.inverse();
  PointCloud recent_imu;
  for (const PointCloud& sweep : recent_search_) {
    const PointCloud sweep_imu = Transformed(T_imu_search, sweep);
    recent_imu.insert(recent_imu.end(), sweep_imu.begin(), sweep_imu.end());
  }
  return recent_imu;
}

bool MovingSearch::GaveUp() const {
  return options_.max_distance_m > 0.0 && distance_m_ > options_.max_distance_m;
}

}  // namespace hylo::localization
