#pragma once
// Pieces of the ICP initializer kept out of the public header: the hypothesis grid, the
// acceptance measures and the pose distance used to tell results apart.

#include <Eigen/Geometry>
#include <vector>

#include "hylo/localization/icp_initializer.h"
#include "hylo/registration/plane_matcher.h"

namespace hylo::localization::internal {

/// Every k-th point so that at most `max_points` remain: after a voxel filter the points are
/// already spread evenly, and a stride keeps that spread.
PointCloud Decimate(const PointCloud& cloud, int max_points);

/// One start pose for the search, as an offset from the guess.
struct Hypothesis {
  double dx_m = 0.0;      ///< map x offset of the position, m
  double dy_m = 0.0;      ///< map y offset, m
  double dyaw_rad = 0.0;  ///< rotation about map z through the guessed position, rad
};

/// The yaw x position grid around the guess, the guess itself first, then by growing offset
/// (normalised by the ranges), at most options.max_hypotheses entries.
std::vector<Hypothesis> MakeHypotheses(const IcpInitializerOptions& options);

/// The start pose of `h`: roll and pitch of the guess are kept (they come from gravity).
Eigen::Isometry3d ApplyHypothesis(const Eigen::Isometry3d& T_map_imu_guess, const Hypothesis& h);

/// Local map plane of a point: 5 map neighbours (as FAST-LIO2's matcher) within a metre, all
/// within 10 cm of their plane.
constexpr int kPlaneNeighbors = 5;
constexpr float kPlaneRadiusM = 1.0f;
constexpr double kPlanarityM = 0.1;

/// The plane of the map around `q_map` when its nearest map point lies within `max_nn_m`;
/// *nn_squared_m2 receives that point's squared distance (when there is one within
/// max(max_nn_m, kPlaneRadiusM)). `neighbors` is scratch space.
bool LocalPlane(const registration::NeighborSearch& map, const Eigen::Vector3d& q_map, double max_nn_m,
                std::vector<registration::Neighbor>* neighbors, double* nn_squared_m2, registration::Plane* plane);

/// Point-to-plane Gauss-Newton from `T_map_source` (the ICP's result): each source point with
/// a map point within `max_nn_m` pulls towards its LocalPlane, with Cauchy weights of scale
/// 0.1 m. Point-to-point ICP converges slowly along surfaces and settles where the map's
/// points, not its surfaces, lie (a centimetre-scale pull per metre of map spacing); this
/// removes both. At most `max_iterations`; stops below 1e-4 m and 1e-5 rad steps.
Eigen::Isometry3d PlaneRefine(const PointCloud& source, const registration::NeighborSearch& map,
                              const Eigen::Isometry3d& T_map_source, double max_nn_m,
                              int max_iterations);

/// The gates' measures of one pose.
struct PoseQuality {
  double fitness_score_m2 = 0.0;  ///< mean squared NN distance within fitness_max_range_m
  double plane_fitness_m2 = 0.0;  ///< mean squared point-to-plane residual of the inliers with
                                  ///< a local map plane (1 when there is none)
  double inlier_ratio = 0.0;      ///< share of finite points within inlier_distance_m
  double constraint = 0.0;        ///< weakest normalised information eigenvalue
};

/// Fitness and inlier ratio only (cheap: one NN query per point).
PoseQuality MeasureOverlap(const PointCloud& source, const registration::NeighborSearch& map,
                           const Eigen::Isometry3d& T_map_source,
                           const IcpInitializerOptions& options);

/// Every measure in one pass (the k nearest map points of each scan point give its nearest
/// distance and its local plane). The plane fitness is the paper's fitness with the map's
/// sampling taken out: a perfectly placed point lies on the map's surface but, in general,
/// between its points, so its nearest-point distance grows with the map's spacing (a 0.2 m
/// grid alone gives ~0.007 m^2) while its distance to the local plane does not.
/// The constraint is the weakest eigenvalue of H / N, H = sum_i J_i^T J_i over the inliers
/// with a local map plane, J_i = [ ((q_i - c) x n_i)^T / L, n_i^T ]: the point-to-plane
/// Jacobian of a small rotation about the centroid c and a translation, the rotation scaled by
/// the RMS radius L so both move an average point by the same amount (Zhang, Kaess & Singh,
/// "On degeneracy of optimization-based state estimation problems", ICRA 2016). N counts all
/// finite points, so a direction seen by few points is weak. 0 for fewer than 6 planes.
PoseQuality MeasureQuality(const PointCloud& source, const registration::NeighborSearch& map,
                           const Eigen::Isometry3d& T_map_source,
                           const IcpInitializerOptions& options);

/// True when the poses differ by more than either bound.
bool AreDistinct(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double translation_m,
                 double rotation_rad);

}  // namespace hylo::localization::internal
