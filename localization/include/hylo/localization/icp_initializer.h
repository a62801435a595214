#pragma once
// ICP initializer for localization in a prior map (Alamanos et al., Sec. III: the first
// scans, taken at rest, are registered to the prior map by point-to-point ICP from a rough
// guess, and the result is accepted only under a Euclidean fitness threshold of 0.01 m^2).
//
// Frames and composition. The caller accumulates the static scans *in the IMU frame*
// (p_imu = T_imu_lidar * p_lidar, with the lidar-IMU extrinsic) and passes the map in the map
// frame, so the result is T_map_imu directly; the lidar pose is T_map_imu * T_imu_lidar.
// Gravity: at rest the IMU's mean specific force points up, which fixes roll and pitch of the
// guess (GuessFromGravity); yaw and position come from the user. ICP then refines all 6 DoF.
//
// The fitness gate measures point-to-plane, not the paper's point-to-point distance. A scan
// placed exactly right lies on the map's surfaces, but between the map's points: its mean
// squared nearest-point distance grows with the map's spacing (a 0.2 m ground grid alone gives
// ~0.007 m^2, and on the simulated substation right poses spread over 0.002-0.02 m^2 where the
// site changed, overlapping wrong places from 0.014 m^2 on). The distance to the plane of the
// nearest map points does not carry that spacing: right poses stay below 0.0023 m^2, wrong
// places above 0.0074 m^2 (the global localization benchmark's seed 11). The paper's fitness
// is still measured and reported, and can be made a gate again (fitness_threshold_m2).
//
// Why more than a fitness gate. A substation is mostly gravel: away from the true
// place the ground alone can give a low mean squared distance, and a partial overlap (few
// points matched, all close) too. Acceptance therefore also requires
//  - an inlier ratio: the share of all scan points with a map point within inlier_distance_m
//    (a wrong place leaves the returns of gantries, fences and buildings unmatched);
//  - a constraint measure: the weakest direction of the point-to-plane information at the
//    result (a flat or corridor-like view leaves yaw or a translation unobservable, and ICP
//    then "converges" anywhere along it with a perfect fitness);
//  - uniqueness (search only): two distinct accepted poses mean the site is ambiguous from
//    this view, and neither is reported.
// If the guess fails, a bounded set of hypotheses (yaw sweep x position grid around the guess)
// is tried with a coarse ICP (downsampled scan, wide correspondence distance); the best few
// distinct results are refined by the fine ICP and gated as above.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <string>

#include "hylo/common/point_types.h"
#include "hylo/registration/icp.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::localization {

struct IcpInitializerOptions {
  IcpInitializerOptions();

  // --- acceptance gates (all must pass) ---
  double plane_fitness_threshold_m2 = 0.004;  ///< mean squared distance of the inliers to the
                                              ///< plane of their nearest map points (those
                                              ///< with a planar neighbourhood) must be below
                                              ///< this, m^2, > 0
  double fitness_threshold_m2 = 0.0;          ///< the paper's Euclidean fitness (mean squared NN
                                              ///< distance) must be below this, m^2 (paper: 0.01);
                                              ///< 0 = measured, not a gate (see above), >= 0
  double fitness_max_range_m = 0.5;  ///< points farther than this from the map are left out
                                     ///< of the fitness mean (objects absent from the prior
                                     ///< map: the inlier ratio accounts for them), m, > 0
  double inlier_distance_m = 0.3;    ///< a scan point is an inlier when a map point lies
                                     ///< within this, m (3x the RMS distance the fitness
                                     ///< threshold allows), > 0
  double min_inlier_ratio = 0.75;    ///< inliers / finite scan points must reach this, (0, 1]
  double min_constraint = 0.01;      ///< weakest eigenvalue of the normalised point-to-plane
                                     ///< information (0 = a free direction, 1 = every point
                                     ///< constrains it fully) must reach this, [0, 1)
  int min_source_points = 50;        ///< fewer finite scan points (after fine_voxel_m) are
                                     ///< rejected outright, >= 3

  // --- fine ICP (the paper's step) ---
  double fine_voxel_m = 0.2;   ///< scan downsampling before the fine ICP, m (0 = none), >= 0
  int fine_max_points = 5000;  ///< at most this many scan points (even stride after the voxel
                               ///< filter) in the fine ICP and the gates, >= min_source_points
  registration::Icp::Options fine_icp;       ///< fine ICP; its fitness_max_range_m is not used (see above)
  int plane_refine_iterations = 10;  ///< point-to-plane steps after the fine ICP (the ICP
                                     ///< settles centimetres off where the map is sparse or
                                     ///< changed), 0 = none, >= 0

  // --- bounded search around the guess when the guess itself fails ---
  bool search_enabled = true;      ///< false: only the guess is tried
  double yaw_range_deg = 30.0;     ///< hypotheses at yaw offsets within +-this, deg, [0, 180]
  double yaw_step_deg = 15.0;      ///< yaw offset step, deg, > 0 (a start is then at most
                                   ///< 7.5 deg from a hypothesis: inside the coarse basin)
  double position_range_m = 2.0;   ///< x/y offsets within +-this (map frame), m, >= 0
  double position_step_m = 2.0;    ///< x/y offset step, m, > 0 (at most 1.4 m from a
                                   ///< hypothesis, half the coarse correspondence distance)
  double coarse_voxel_m = 1.0;     ///< scan downsampling for the coarse ICP, m, >= fine_voxel_m
  int coarse_max_points = 500;     ///< at most this many points (even stride) in the coarse
                                   ///< ICP: it only has to land in the fine basin, >= 3
  registration::Icp::Options coarse_icp;         ///< coarse ICP: wide correspondences, few iterations
  int max_refined_candidates = 4;  ///< distinct coarse results refined by the fine ICP, >= 1
  double distinct_translation_m = 0.5;  ///< poses farther apart (or ...) are distinct, m, > 0
  double distinct_rotation_deg = 5.0;   ///< ... rotated more than this are distinct, deg, > 0
  bool reject_ambiguous = true;         ///< two distinct accepted poses: reject (report both)
  int max_hypotheses = 2000;            ///< bound on yaw x position hypotheses, >= 1

  bool IsValid(std::string* why) const;
};

/// What the initializer decided. When `accepted` is false, T_map_imu is the guess unchanged:
/// it must not be used as a pose; the best_* fields say how close the search came.
struct IcpInitializerResult {
  bool accepted = false;
  Eigen::Isometry3d T_map_imu = Eigen::Isometry3d::Identity();        ///< accepted pose (see above)
  double fitness_score_m2 = std::numeric_limits<double>::infinity();  ///< at T_map_imu, m^2
  double plane_fitness_m2 = std::numeric_limits<double>::infinity();  ///< at T_map_imu, m^2
  double inlier_ratio = 0.0;                                          ///< at T_map_imu, [0, 1]
  double constraint = 0.0;           ///< weakest normalised information eigenvalue, [0, 1]
  int hypotheses_tried = 0;          ///< ICP runs started (1 = only the guess)
  int accepted_hypothesis = -1;      ///< -1 none, 0 the guess itself, k > 0 the k-th search offset
  double hypothesis_dx_m = 0.0;      ///< offset of the accepted hypothesis from the guess, map x, m
  double hypothesis_dy_m = 0.0;      ///< ... map y, m
  double hypothesis_dyaw_deg = 0.0;  ///< ... yaw about map z, deg
  int num_accepted_distinct = 0;     ///< distinct poses that passed every gate
  std::size_t num_source_points = 0;  ///< finite scan points after fine_voxel_m
  // Diagnostics of the best candidate when nothing was accepted (inf / 0 otherwise unset).
  double best_fitness_score_m2 = std::numeric_limits<double>::infinity();  ///< m^2
  double best_plane_fitness_m2 = std::numeric_limits<double>::infinity();  ///< m^2
  double best_inlier_ratio = 0.0;
  double best_constraint = 0.0;
  /// Where the best candidate's ICP ended when nothing was accepted: diagnostics (how far a
  /// rejected hypothesis is from the truth), never a pose to use.
  Eigen::Isometry3d best_T_map_imu = Eigen::Isometry3d::Identity();
  std::string message;     ///< one line: why accepted or rejected
  double elapsed_s = 0.0;  ///< wall time of Initialize, s
};

class IcpInitializer {
 public:
  /// Throws hylo::InternalError naming the field when `options` is not valid.
  explicit IcpInitializer(const IcpInitializerOptions& options = IcpInitializerOptions());

  /// Registers the accumulated static scans `scan_imu` (IMU frame) to `map` (map frame)
  /// starting from `T_map_imu_guess`. Bad input (no finite point, empty map, non-finite
  /// guess) gives accepted = false and a message; it never throws.
  IcpInitializerResult Initialize(const PointCloud& scan_imu, const registration::NeighborSearch& map,
                                  const Eigen::Isometry3d& T_map_imu_guess) const;

  const IcpInitializerOptions& options() const { return options_; }

 private:
  IcpInitializerOptions options_;
};

/// A guess whose roll and pitch come from gravity: `mean_specific_force_imu` is the IMU's
/// mean accelerometer reading at rest (it points up, opposite to gravity). The rotation is
/// Rz(yaw) * R_level, where R_level is the smallest rotation taking that direction onto map
/// +z, so `yaw_rad` is the heading about map z after levelling. Throws hylo::InternalError
/// for a zero or non-finite force.
Eigen::Isometry3d GuessFromGravity(const Eigen::Vector3d& position_map, double yaw_rad,
                                   const Eigen::Vector3d& mean_specific_force_imu);

}  // namespace hylo::localization
