#pragma once
// Offline map crafting: a raw SLAM map (thick, noisy, unevenly dense) becomes a clean map by
// uniform sampling (one original point per voxel, registration/voxel_filter.h) and moving
// least squares smoothing (points projected onto a local polynomial surface, with normals).
// The sampled points are projected, but the MLS fits use the denser raw map (thinned to
// mls_support_voxel_m) as their data: more points per neighbourhood average more noise away.
// With mls_small_radius_m > 0, each point takes the large-radius fit only where it agrees with
// a small-radius fit within their confidence intervals (craft_mls.cpp), so poles and thin
// parts seen from all sides are not pulled towards their axes.

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace hylo::terrain {

struct CraftOptions {
  double voxel_size_m = 0.05;             ///< uniform sampling voxel edge, m (0 = no sampling)
  double mls_search_radius_m = 0.15;      ///< MLS neighbourhood radius, m (> 0; a few voxels)
  double mls_support_voxel_m = 0.0125;    ///< MLS data: the input thinned to one point per voxel
                                          ///< of this edge, m (0 = every input point; >=
                                          ///< voxel_size_m = the sampled points only)
  double mls_small_radius_m = 0.075;      ///< smaller MLS radius for points where the large fit is
                                          ///< inconsistent, m (0 = single-scale PCL MLS;
                                          ///< < mls_search_radius_m)
  double scale_consistency_sigmas = 3.0;  ///< half-width of the scale test's confidence
                                          ///< intervals, standard deviations (> 0)
  int polynomial_order = 2;               ///< MLS surface polynomial order, 0..3 (0 = plane only)
  int num_threads = 1;                    ///< MLS worker threads (>= 1)
  bool compute_normals = true;            ///< output MLS surface normals

  /// False (with the field, its value and the constraint in *why) when a field is out of range.
  bool IsValid(std::string* why) const;
};

struct CraftResult {
  bool ok = false;                            ///< false: nothing produced, see message
  std::string message;                        ///< why not ok, or a one-line description
  std::vector<Eigen::Vector3d> points_world;  ///< smoothed points, input frame, m
  std::vector<Eigen::Vector3f> normals;       ///< unit normals (empty without compute_normals)
  std::size_t num_input = 0;                  ///< points given
  std::size_t num_invalid = 0;                ///< non-finite input points, dropped
  std::size_t num_sampled = 0;                ///< points after uniform sampling
  std::size_t num_dropped_by_mls = 0;         ///< sampled points MLS could not fit (too few
                                              ///< neighbours within the radius), dropped
  std::size_t num_support = 0;                ///< points MLS fitted to (support + sampled)
  std::size_t num_small_scale = 0;            ///< output points that took the small radius
  double sampling_seconds = 0.0;              ///< wall time of uniform sampling, s
  double mls_seconds = 0.0;                   ///< wall time of MLS, s
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();  ///< shift used to compute near zero
};

/// Samples and smooths `points_world` (may be UTM-sized: the work is done near an origin and
/// shifted back). Empty or all-NaN input gives ok = false. Throws std::invalid_argument when
/// options are invalid.
CraftResult CraftMap(const std::vector<Eigen::Vector3d>& points_world, const CraftOptions& options);

}  // namespace hylo::terrain
