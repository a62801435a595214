#pragma once
// Searching while moving: what the localization start does when the global localizer finds
// the view ambiguous (symmetric bays: two places fit equally) or finds no place at all, instead
// of picking one. Odometry runs on — the pipeline's own estimator, registered against a
// scratch map built from the scans themselves, in a provisional "search" frame (gravity
// levelled, z up, like the map) — the registered scans are accumulated, and the global
// localizer is tried again on the longer cloud each time the vehicle has moved `retry_m`.
// A farther view sees what tells the look-alikes apart. The first attempt that the global
// localizer accepts places the search frame in the map (T_map_search), and the estimator goes
// on in the prior from there; until then no pose is reported.

#include <Eigen/Geometry>
#include <deque>
#include <memory>

#include "hylo/common/point_types.h"
#include "hylo/localization/localization.h"
#include "hylo/mapping/map_manager.h"
#include "hylo/registration/plane_matcher.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::localization {

class MovingSearch {
 public:
  /// `map` and `planes`: the run's own map and plane settings, used for the scratch map;
  /// `keep_radius_m`: accumulated points farther than this from the vehicle are dropped (the
  /// global localizer's max range: it would not look at them).
  MovingSearch(const MovingSearchOptions& options, const mapping::MapManagerOptions& map,
               const registration::PlaneMatcherOptions& planes, double keep_radius_m,
               int recent_scans);

  /// Seeds the scratch map and the cloud with `points_imu` seen from `T_search_imu`.
  void Begin(const PointCloud& points_imu, const Eigen::Isometry3d& T_search_imu);
  /// What the estimator registers against while searching.
  const registration::PlaneMatcher& matcher() const { return *matcher_; }

  /// Adds a registered scan seen from `T_search_imu`: `sweep_imu`, the whole deskewed scan
  /// (IMU frame), to the accumulated cloud, and `map_points_search`, what the odometry would
  /// add to its map (search frame; empty when its update failed), to the scratch map. True
  /// when a global attempt is due: the vehicle is retry_m (straight line: jitter at rest adds
  /// up along a path) from where the last one was made, or (`first_attempt_scans` > 0) that
  /// many scans were added since Begin and no attempt was made yet.
  bool Add(const PointCloud& sweep_imu, const PointCloud& map_points_search,
           const Eigen::Isometry3d& T_search_imu, int first_attempt_scans);
  /// For an attempt at `T_search_imu`: the accumulated cloud within keep_radius_m of the
  /// vehicle, in its IMU frame (farther points are dropped for good, so memory stays bounded
  /// on a long search). The next attempt is due retry_m farther on.
  PointCloud TakeAttemptCloud(const Eigen::Isometry3d& T_search_imu);
  /// The last `recent_scans` sweeps alone, in the IMU frame at `T_search_imu`: the view that
  /// places the vehicle now, free of the drift the search's odometry gathered farther back.
  PointCloud RecentInImu(const Eigen::Isometry3d& T_search_imu) const;

  double distance_m() const { return distance_m_; }  ///< travelled since Begin, m
  int scans() const { return scans_; }               ///< sweeps added since Begin
  int attempts() const { return attempts_; }
  /// True when max_distance_m is set and exceeded.
  bool GaveUp() const;

 private:
  MovingSearchOptions options_;
  double keep_radius_m_;
  mapping::MapManager map_;
  std::unique_ptr<registration::PlaneMatcher> matcher_;  // on map_
  registration::UniformSampler cloud_search_;            // accumulated, search frame
  int recent_scans_;
  std::deque<PointCloud> recent_search_;  // the last sweeps, search frame
  Eigen::Vector3d last_position_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d attempt_position_ = Eigen::Vector3d::Zero();  // of the last attempt (Begin's)
  double distance_m_ = 0.0;
  int scans_ = 0;
  int attempts_ = 0;
};

}  // namespace hylo::localization
