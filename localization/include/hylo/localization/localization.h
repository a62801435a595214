#pragma once
// Localization in a prior map (Alamanos et al., Sec. III): what the odometry pipeline adds when
// it is given a prior map and an initial guess. The pieces are shared by every back-end:
//  - start: the first scans (at rest, while the IMU initialises) are accumulated in the IMU
//    frame and registered to the prior by the ICP initializer; odometry starts only from an
//    accepted pose, never from the guess itself;
//  - hybrid mode: after `update_after_s` seconds of localization, registered scans are added
//    to the map (the run's tree, beside the never-windowed prior), so changed or unexplored
//    parts of the site extend the map aligned with the prior;
//  - health: per scan, from the update's own residuals at its final pose: the share of the
//    scan's points that lie on a map surface (inlier ratio), their mean squared residual
//    (fitness) and the number of plane matches; `lost_after_scans` bad scans in a row (or a
//    user request) start a relocalization: the initializer runs around the current pose.
//    Each event is recorded for the run's summary;
//  - global start: without a guess, or when the guess is rejected, the global localizer
//    (global_localizer.h) searches the whole prior map for the static scans and
//    its verdict (accepted, ambiguous, not found) is the start's.

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <string>

#include "hylo/estimation/estimator.h"
#include "hylo/localization/global_localizer.h"
#include "hylo/localization/global_map.h"
#include "hylo/localization/icp_initializer.h"

namespace hylo::localization {

/// Searching while moving (moving_search.h): what the start does when the global
/// localizer finds the view ambiguous or finds nothing.
struct MovingSearchOptions {
  bool enabled = true;          ///< false: such a start fails at once (no pose is guessed)
  double retry_m = 3.0;         ///< travel between two global attempts on the longer cloud, m,
                                ///< > 0 (each attempt costs a global localization's CPU)
  double max_distance_m = 0.0;  ///< give up (the start fails) after this travel, m; 0 = search
                                ///< for as long as the vehicle moves, >= 0
  double voxel_m = 0.2;         ///< the accumulated cloud keeps one point per voxel, m, > 0
  /// Each global attempt runs on a worker thread while the scans go on being tracked in the
  /// provisional frame (background_search.h), and the scans the attempts look at are
  /// accumulated on another (moving_search.h): a live vehicle's scan path is not stalled by a
  /// search. Off, an attempt runs on the scan thread, and a log read from a file gives the
  /// same result on every run whatever the machine's load. Not with a tiled prior (its tiles
  /// change under the scan thread): attempts then run on the scan thread. The ROS node always
  /// searches in the background.
  bool background = false;

  bool IsValid(std::string* why) const;
};

struct LocalizationOptions {
  int init_scans = 10;           ///< static scans accumulated for the ICP initializer (with an
                                 ///< IMU; without one only the first scan is used), >= 1
  double update_after_s = -1.0;  ///< hybrid mode: seconds after the start of localization
                                 ///< from which scans are added to the map; -1 = never
                                 ///< (localization only), else >= 0
  IcpInitializerOptions icp;  ///< start and relocalization
  bool global_enabled = true;  ///< search the whole prior map when there is no guess or the
                               ///< guess is rejected; false: the guess alone
  GlobalLocalizerOptions global;  ///< that search (its refinement uses `icp`)
  GlobalMapOptions global_map;    ///< the raster of the prior map it searches
  MovingSearchOptions search;                   ///< when that search is ambiguous or finds nothing

  // --- health, computed on every scan from the update's residuals ---
  /// A registered point is an inlier when the plane the update matched it to (its nearest map
  /// points, PlaneMatcher settings) lies within this of it at the final pose, m (> 0). A
  /// point-to-point test alone passes scans several degrees off in a dense map (balm_scans:
  /// 61 % of points within 0.3 m of a map point at 5°).
  double health_inlier_distance_m = 0.1;
  double health_max_range_m = 1.0;  ///< larger residuals are left out of the fitness, m,
                                    ///< >= health_inlier_distance_m
  double min_inlier_ratio = 0.5;    ///< below this share of the scan's points a scan is
                                    ///< bad, [0, 1]
  int min_matches = 50;             ///< fewer plane matches: the scan is bad, >= 0
  int lost_after_scans = 5;         ///< bad scans in a row before relocalizing, >= 1
  int relocalize_retry_scans = 10;  ///< scans between two failed relocalizations, >= 1

  bool IsValid(std::string* why) const;
};

/// How well one registered scan fits the map (after the update).
struct ScanHealth {
  double fitness_m2 = std::numeric_limits<double>::quiet_NaN();  ///< mean squared residual of
                                                                 ///< the matched points within
                                                                 ///< health_max_range_m, m²
  double inlier_ratio = 0.0;    ///< share of the scan's points with their matched plane
                                ///< within health_inlier_distance_m, [0, 1]
  std::size_t num_matches = 0;  ///< plane matches of the update
  bool good = false;            ///< passes min_inlier_ratio and min_matches
};

/// Something the localizer decided, for the run's summary and the ROS health topic.
struct LocalizationEvent {
  enum class Kind {
    kInitialized,           ///< the ICP initializer accepted a start pose
    kInitializationFailed,  ///< no start pose passed the gates: no odometry
    kLost,                  ///< lost_after_scans bad scans in a row
    kRelocalized,           ///< a relocalization was accepted (pose reset)
    kRelocalizationFailed,  ///< ... was rejected (retried later)
    kHybridStarted,         ///< scans are now added to the map
    kLeftMap,               ///< the vehicle left the tiled prior's tiles: odometry only
    kReenteredMap,          ///< ... and came back onto them: localization again
    kSearching,             ///< no pose yet (ambiguous or not found, or a global localization
                            ///< was requested): odometry on its own map, the global localizer
                            ///< retried while the vehicle moves
  };
  Kind kind = Kind::kInitialized;
  int64_t t_ns = 0;  ///< scan end time of the decision, ns
  Eigen::Isometry3d T_map_imu = Eigen::Isometry3d::Identity();         ///< pose after the event
  double fitness_m2 = std::numeric_limits<double>::quiet_NaN();        ///< initializer fitness, m²
  double plane_fitness_m2 = std::numeric_limits<double>::quiet_NaN();  ///< ... plane fitness,
                                                                       ///< m² (the gate)
  double inlier_ratio = 0.0;                                           ///< initializer inlier ratio
  std::string message;                                                 ///< one line, why
};

/// The health of a scan from its update (residuals at the final pose, taken before the scan
/// itself is added to the map).
ScanHealth EvaluateScanHealth(const estimation::UpdateSummary& update, const LocalizationOptions& options);

/// "initialized", "initialization_failed", "lost", "relocalized", "relocalization_failed",
/// "hybrid_started", "left_map", "reentered_map", "searching".
std::string ToString(LocalizationEvent::Kind kind);

}  // namespace hylo::localization
