#pragma once
// Voxel-grid downsampling shared by the scan pre-processing, the map and map crafting.

#include "hylo/registration/point_types.h"

namespace hylo::registration {

/// Uniform sampling: per occupied voxel of edge `voxel_size_m`, keep the input point nearest
/// the voxel centre (an original point, not an average, so surfaces are not blurred).
/// Output order follows the first appearance of each voxel in the input. voxel_size_m <= 0
/// returns the input unchanged.
PointCloud UniformSample(const PointCloud& points, float voxel_size_m);

/// Indices (into `points`) of the points UniformSample keeps, for callers carrying attributes.
std::vector<std::size_t> UniformSampleIndices(const PointCloud& points, float voxel_size_m);

}  // namespace hylo::registration
