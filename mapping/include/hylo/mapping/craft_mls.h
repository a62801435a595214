#pragma once
// Moving least squares on the project's own types. PCL (pcl::MovingLeastSquares) is used only
// inside craft_mls.cpp; nothing of it leaks through this header.

#include <Eigen/Core>
#include <vector>

#include "hylo/registration/point_types.h"

namespace hylo::mapping {

struct MlsOutput {
  registration::PointCloud points;       ///< projected points (near-zero frame), m
  std::vector<Eigen::Vector3f> normals;  ///< unit normals, one per point (when requested)
};

/// Projects every point of `points_local` (finite, near zero) onto its local MLS polynomial;
/// points whose neighbourhood is too small to fit are left out of the output.
MlsOutput SmoothMls(const registration::PointCloud& points_local, double search_radius_m,
                    int polynomial_order, int num_threads, bool compute_normals);

}  // namespace hylo::mapping
