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
#include <functional>
#include <future>
#include <memory>

#include "hylo/common/point_types.h"
#include "hylo/localization/attempt_cloud.h"
#include "hylo/localization/localization.h"
#include "hylo/localization/serial_worker.h"
#include "hylo/mapping/map_manager.h"
#include "hylo/registration/plane_matcher.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::localization {

class MovingSearch {
 public:
  /// `map` and `planes`: the run's own map and plane settings, used for the scratch map;
  /// `keep_radius_m`: accumulated points farther than this from the vehicle are dropped (the
  /// global localizer's max range: it would not look at them). `accumulate_on_worker`: the
  /// scans are accumulated on a thread of the search's own (in order), off the scan path;
  /// false: on the caller's thread, each Add done when it returns.
  MovingSearch(const MovingSearchOptions& options, const mapping::MapManagerOptions& map,
               const registration::PlaneMatcherOptions& planes, double keep_radius_m,
               int recent_scans, bool accumulate_on_worker);

  /// Seeds the scratch map and the cloud with `points_imu` seen from `T_search_imu`.
  void Begin(const PointCloud& points_imu, const Eigen::Isometry3d& T_search_imu);
  /// What the estimator registers against while searching.
  const registration::PlaneMatcher& matcher() const { return *matcher_; }

  /// Adds a registered scan seen from `T_search_imu`: `map_points_search`, what the odometry
  /// would add to its map (search frame; empty when its update failed), to the scratch map at
  /// once, and the sweep `sweep_imu` makes (the whole deskewed scan, IMU frame; made where the
  /// scans are accumulated) to the accumulated cloud. True when a global attempt is due: the
  /// vehicle is retry_m (straight line: jitter at rest adds up along a path) from where the
  /// last one was made, or (`first_attempt_scans` > 0) that many scans were added since Begin
  /// and no attempt was made yet.
  bool Add(std::function<PointCloud()> sweep_imu, const PointCloud& map_points_search,
           const Eigen::Isometry3d& T_search_imu, int first_attempt_scans);
  /// For an attempt at `T_search_imu`, once the scans added before are accumulated: the
  /// accumulated cloud within keep_radius_m of the vehicle, to be moved to its IMU frame where
  /// the attempt runs, and the last `recent_scans` sweeps alone (the view that places the
  /// vehicle now, free of the drift the search's odometry gathered farther back). Points
  /// farther than keep_radius_m are dropped for good, so memory stays bounded on a long
  /// search. The next attempt is due retry_m farther on.
  std::shared_future<AttemptClouds> TakeAttemptClouds(const Eigen::Isometry3d& T_search_imu);

  double distance_m() const { return distance_m_; }  ///< travelled since Begin, m
  int scans() const { return scans_; }               ///< sweeps added since Begin
  int attempts() const { return attempts_; }
  /// True when max_distance_m is set and exceeded.
  bool GaveUp() const;

 private:
  // The accumulated points within keep_radius_m of `center_search` (search frame); the others
  // are dropped for good.
  PointCloud KeepNear(const Eigen::Vector3f& center_search);

  MovingSearchOptions options_;
  double keep_radius_m_;
  mapping::MapManager map_;
  std::unique_ptr<registration::PlaneMatcher> matcher_;  // on map_
  int recent_scans_;
  Eigen::Vector3d last_position_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d attempt_position_ = Eigen::Vector3d::Zero();  // of the last attempt (Begin's)
  double distance_m_ = 0.0;
  int scans_ = 0;
  int attempts_ = 0;
  // Touched only by the accumulation's jobs once Begin has returned.
  registration::UniformSampler cloud_search_;  // accumulated, search frame
  std::deque<PointCloud> recent_search_;       // the last sweeps, search frame
  // Last: destroyed first, it runs the jobs still queued while what they touch exists.
  SerialWorker accumulation_;
};

}  // namespace hylo::localization
