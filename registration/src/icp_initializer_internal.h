#pragma once
// Pieces of the ICP initializer kept out of the public header: the hypothesis grid, the
// acceptance measures and the pose distance used to tell results apart.

#include <Eigen/Geometry>
#include <vector>

#include "hylo/registration/icp_initializer.h"

namespace hylo::registration::internal {

/// One start pose for the search, as an offset from the guess.
struct Hypothesis {
  double dx_m = 0.0;     ///< map x offset of the position, m
  double dy_m = 0.0;     ///< map y offset, m
  double dyaw_rad = 0.0; ///< rotation about map z through the guessed position, rad
};

/// The yaw x position grid around the guess, the guess itself first, then by growing offset
/// (normalised by the ranges), at most options.max_hypotheses entries.
std::vector<Hypothesis> MakeHypotheses(const IcpInitializerOptions& options);

/// The start pose of `h`: roll and pitch of the guess are kept (they come from gravity).
Eigen::Isometry3d ApplyHypothesis(const Eigen::Isometry3d& T_map_imu_guess, const Hypothesis& h);

/// The gates' measures of one pose.
struct PoseQuality {
  double fitness_score_m2 = 0.0;  ///< mean squared NN distance within fitness_max_range_m
  double inlier_ratio = 0.0;      ///< share of finite points within inlier_distance_m
  double constraint = 0.0;        ///< weakest normalised information eigenvalue
};

/// Fitness and inlier ratio only (cheap: one NN query per point).
PoseQuality MeasureOverlap(const PointCloud& source, const NeighborSearch& map,
                           const Eigen::Isometry3d& T_map_source,
                           const IcpInitializerOptions& options);

/// Weakest eigenvalue of H / N, H = sum_i J_i^T J_i over the inliers with a local map plane,
/// J_i = [ ((q_i - c) x n_i)^T / L, n_i^T ]: the point-to-plane Jacobian of a small rotation
/// about the centroid c and a translation, the rotation scaled by the RMS radius L so both
/// move an average point by the same amount (Zhang, Kaess & Singh, "On degeneracy of
/// optimization-based state estimation problems", ICRA 2016). N counts all finite points, so
/// a direction seen by few points is weak. 0 for fewer than 6 planes.
double ConstraintMeasure(const PointCloud& source, const NeighborSearch& map,
                         const Eigen::Isometry3d& T_map_source, double inlier_distance_m);

/// True when the poses differ by more than either bound.
bool AreDistinct(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double translation_m,
                 double rotation_rad);

}  // namespace hylo::registration::internal
