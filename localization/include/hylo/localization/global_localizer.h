#pragma once
// Global localization: the pose of a vehicle in the prior map without a guess.
//
// Input: scans in the IMU frame (the static scans of the start, or a cloud accumulated by
// odometry while moving) and the rotation that levels the IMU frame (from gravity at rest, or
// the estimator's roll and pitch; without an IMU the identity: a ground vehicle starting near
// level). Four degrees of freedom are then left: x, y, yaw and z, and z is not searched: the
// vehicle stands on the map's ground, so z = the lowest map point of the candidate's cell +
// the sensor's height above its own ground (a constant of the vehicle when it is given,
// otherwise read from the scan).
//
// 1. Search (branch and bound, Hess et al. 2016 Sec. V, Algorithm 3): the levelled scan is
//    cut into voxels (a cell of the GlobalMap and a height bin relative to the vehicle's
//    ground); at each sampled yaw, a pose scores the voxels whose height bin holds map points
//    in the map cell they fall on (within z_tolerance_m). The GlobalMap's pyramid bounds whole
//    2^k x 2^k blocks of positions at once, so the best poses are found exactly (for the
//    sampled yaws) without scoring every position. The search keeps the best
//    `max_hypotheses` mutually distinct poses, ranked.
// 2. Refinement and judgement: each hypothesis scoring at least refine_score_ratio x the best
//    is pulled in by a coarse ICP on a sparse cloud (cheap: a few hundred points); the
//    fine_hypotheses distinct ones with the largest share of points near the map then go
//    through the ICP initializer from there (fine ICP and point-to-plane steps on a thinned
//    scan, no local search) and its gates (plane fitness, inlier ratio, constraint). The gates
//    are the judge, with one of its own: the ground the vehicle stands on must be in the map
//    (min_ground_support), since a vehicle parked beside the mapped area may still see
//    enough of the map's structures to pass the others.
//     - none passes: not found (outside the map, or a view too poor to tell);
//     - the distinct refined pose with the next best inlier ratio (passing or not) comes
//       within ambiguity_inlier_margin of the best passing pose's: ambiguous (symmetric bays),
//       and no pose is returned; the caller waits for more data (a longer accumulated cloud);
//     - otherwise the best passing pose is accepted (its point-to-plane refinement places it
//       within centimetres: a second pass with more points changed nothing measurable).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/localization/global_map.h"
#include "hylo/localization/icp_initializer.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::localization {

struct GlobalLocalizerOptions {
  // --- the scan as the search sees it ---
  double min_range_m = 1.0;         ///< closer points are left out (the vehicle itself), m, >= 0
  double max_range_m = 60.0;        ///< farther points are left out: sparse, and a tilt error moves
                                    ///< them most, m, > min_range_m
  double ground_clearance_m = 0.3;  ///< points less than this above the vehicle's own ground
                                    ///< are left out of the search (they fit any flat ground;
                                    ///< the ICP gates still see them), m; < 0 keeps them
  double sensor_height_m = 0.0;     ///< height of the scan's frame (the IMU) above the ground
                                    ///< under the vehicle's wheels, a constant of the vehicle, m;
                                    ///< 0 = estimated from the scan (the plane through the lowest
                                    ///< returns around it: off by up to 2 m beside a bank), >= 0
  double z_tolerance_m = 0.3;       ///< how far the vehicle's height above the map ground may be
                               ///< off (map ground per cell, sensor height from the scan), m, >= 0
  double yaw_step_deg = 3.0;   ///< yaw sampling, deg; 0 = the angle that moves a point at
                               ///< max_range_m by one cell. The refinement's basin is several
                               ///< times wider than half a step, >= 0
  int max_scan_points = 1000;  ///< at most this many scan points (after a voxel filter of half
                               ///< a cell, even stride) enter the search: the search's cost is
                               ///< proportional to them, >= 10

  // --- hypotheses ---
  int max_hypotheses = 8;               ///< distinct poses kept by the search, >= 1
  double min_score = 0.3;               ///< a hypothesis explains at least this share of the
                                        ///< scan's voxels, (0, 1]
  double distinct_translation_m = 2.0;  ///< poses farther apart are distinct, m, > 0
  double distinct_yaw_deg = 10.0;       ///< ... or turned more than this, deg, > 0

  // --- judgement ---
  double refine_score_ratio = 0.5;        ///< hypotheses scoring >= this x the best go through
                                          ///< the coarse ICP, (0, 1]
  int fine_hypotheses = 4;                ///< the best this many distinct ones after it (by
                                          ///< their share of points near the map) are refined
                                          ///< and gated, >= 1
  double ambiguity_inlier_margin = 0.05;  ///< a refined runner-up within this inlier ratio of
                                          ///< the passing pose makes the view ambiguous, [0, 1]
  double min_ground_support = 0.5;        ///< an accepted pose must explain at least this share of
                                          ///< the vehicle's own ground returns (within 10 m, below
                                          ///< ground_clearance_m): a vehicle beside the map, not on
                                          ///< it, sees far structures of the map but ground the map
                                          ///< never held, [0, 1]
  int judge_max_points = 1500;    ///< scan points in each hypothesis's refinement (at most the
                                  ///< initializer's fine_max_points), >= 50
  int judge_icp_iterations = 30;  ///< at most this many fine ICP iterations there (at most the
                                  ///< initializer's), before its point-to-plane steps, >= 1

  bool IsValid(std::string* why) const;
};

/// One place the search found, with what the refinement made of it.
struct GlobalHypothesis {
  Eigen::Isometry3d T_map_imu = Eigen::Isometry3d::Identity();  ///< the search's pose
  double score = 0.0;  ///< share of the scan's voxels the map explains there, [0, 1]
  Eigen::Isometry3d T_coarse = Eigen::Isometry3d::Identity();  ///< after the coarse ICP
  double coarse_inlier_ratio = 0.0;  ///< of the sparse cloud at T_coarse (0: not run)
  bool refined = false;              ///< went through the ICP initializer
  bool passes = false;               ///< ... and passed every gate
  Eigen::Isometry3d T_refined = Eigen::Isometry3d::Identity();  ///< after ICP (when refined)
  double fitness_m2 = 0.0;        ///< initializer fitness at T_refined, m^2 (when refined)
  double plane_fitness_m2 = 0.0;  ///< initializer plane fitness at T_refined, m^2 (when refined)
  double inlier_ratio = 0.0;      ///< initializer inlier ratio at T_refined (when refined)
  double ground_support = 0.0;    ///< share of the vehicle's ground returns with a map point
                                  ///< within the inlier distance at T_refined (when refined)
};

enum class GlobalStatus {
  kAccepted,   ///< one place passed the gates, clearly ahead of any other
  kAmbiguous,  ///< two or more places fit nearly equally: wait for more data
  kNotFound,   ///< no place passed the gates (outside the map, or too little seen)
  kBadInput,   ///< too few usable scan points, no ground under the vehicle, empty map
};

/// "accepted", "ambiguous", "not_found", "bad_input".
std::string ToString(GlobalStatus status);

struct GlobalSearchStats {
  std::size_t scan_points = 0;     ///< scan points entering the search
  std::size_t scan_voxels = 0;     ///< distinct (cell, height bin) voxels at yaw 0
  int yaws = 0;                    ///< yaw samples
  std::size_t nodes_scored = 0;    ///< branch-and-bound nodes whose bound was computed
  std::size_t columns_scored = 0;  ///< scan columns those bounds looked at (the search's work)
  double sensor_height_m = 0.0;    ///< sensor above the vehicle's ground, from the scan, m
  double search_s = 0.0;           ///< CPU time of the search, s
};

struct GlobalLocalizationResult {
  GlobalStatus status = GlobalStatus::kBadInput;
  Eigen::Isometry3d T_map_imu = Eigen::Isometry3d::Identity();  ///< valid when accepted
  IcpInitializerResult refinement;  ///< the accepted hypothesis's refinement (when accepted)
  std::vector<GlobalHypothesis> hypotheses;  ///< the search's, best score first
  int num_passing = 0;  ///< distinct refined poses that passed the gates (more than
                        ///< one is not ambiguous by itself: see the margin)
  GlobalSearchStats stats;
  double refine_s = 0.0;   ///< CPU time of the refinements, s
  double elapsed_s = 0.0;  ///< CPU time of Localize, s
  std::string message;     ///< one line: the verdict and why
};

class GlobalLocalizer {
 public:
  /// Throws hylo::InternalError naming the field when an options struct is not valid.
  GlobalLocalizer(const GlobalLocalizerOptions& options, const IcpInitializerOptions& icp);

  /// The search alone: ranked distinct hypotheses (unrefined) of `scan_imu` levelled by
  /// `R_level_imu` in `global_map`. Bad input gives no hypothesis.
  std::vector<GlobalHypothesis> Search(const PointCloud& scan_imu,
                                       const Eigen::Matrix3d& R_level_imu,
                                       const GlobalMap& global_map,
                                       GlobalSearchStats* stats = nullptr) const;

  /// Search, refinement and judgement; `map` is the prior map's neighbour search (the same
  /// points as `global_map`). Never throws for bad data.
  GlobalLocalizationResult Localize(const PointCloud& scan_imu, const Eigen::Matrix3d& R_level_imu,
                                    const GlobalMap& global_map, const registration::NeighborSearch& map) const;

  const GlobalLocalizerOptions& options() const { return options_; }

 private:
  GlobalLocalizerOptions options_;
  IcpInitializerOptions icp_;        // search_enabled = false: each hypothesis is its own guess
  IcpInitializerOptions icp_judge_;  // the same with at most judge_max_points scan points
};

/// The rotation that levels an attitude: R_map_imu with its yaw about map z removed, so that
/// Rz(yaw) * LevellingRotation(R) == R for R's own yaw.
Eigen::Matrix3d LevellingRotation(const Eigen::Matrix3d& R_map_imu);

}  // namespace hylo::localization
