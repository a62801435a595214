#pragma once
// Moving least squares on the project's own types. PCL (pcl::MovingLeastSquares, pcl::MLSResult)
// is used only inside craft_mls.cpp; nothing of it leaks through this header.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "hylo/common/point_types.h"

namespace hylo::terrain {

struct MlsSettings {
  double search_radius_m = 0.15;    ///< MLS neighbourhood radius, m
  double small_radius_m = 0.0;      ///< second, smaller scale, m (0 = single-scale PCL MLS)
  double consistency_sigmas = 3.0;  ///< scale test: interval half-width, standard deviations
  int polynomial_order = 2;         ///< MLS polynomial order
  int num_threads = 1;              ///< worker threads
  bool compute_normals = true;      ///< fill MlsOutput::normals
};

struct MlsOutput {
  PointCloud points;                     ///< projected points (near-zero frame), m
  std::vector<Eigen::Vector3f> normals;  ///< unit normals, one per point (when requested)
  std::size_t num_small_scale = 0;       ///< points that took the small-scale fit
};

/// Projects the points `support[queries[k]]` (finite, near zero; `queries` ascending) onto
/// their local MLS polynomials fitted to their neighbours among all of `support`; points whose
/// neighbourhood is too small to fit are left out of the output, which keeps the query order.
MlsOutput SmoothMls(const PointCloud& support, const std::vector<std::size_t>& queries,
                    const MlsSettings& settings);

}  // namespace hylo::terrain
