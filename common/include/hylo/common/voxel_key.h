#pragma once
// The one voxel rule of the project: a point belongs to voxel floor(point / edge) per axis.
// The scan and dense-map samplers (registration/voxel_filter), the ikd-tree's on-tree
// downsampling and its voxel cache all key voxels with these functions, so a point falls into
// the same voxel whichever of them looks at it.

#include <Eigen/Core>
#include <cstdint>

namespace hylo {

using VoxelKey = Eigen::Matrix<int64_t, 3, 1>;

/// floor(x) as an integer without the libm call that x86-64 without SSE4.1 makes of
/// std::floor (a visible share of the samplers' time at three calls per point). `x` must be
/// finite and within the int64 range.
inline int64_t FloorToInt64(float x) {
  const int64_t truncated = static_cast<int64_t>(x);
  return truncated - (x < static_cast<float>(truncated) ? 1 : 0);
}

/// The voxel of `point` for voxels of edge `voxel_size_m` (> 0): floor(point / edge) per axis,
/// computed as point * (1 / edge) so that every caller rounds the same way.
inline VoxelKey VoxelOf(const Eigen::Vector3f& point, float voxel_size_m) {
  const Eigen::Vector3f scaled = point * (1.f / voxel_size_m);
  return {FloorToInt64(scaled.x()), FloorToInt64(scaled.y()), FloorToInt64(scaled.z())};
}

/// The centre of voxel `voxel` for edge `voxel_size_m`, m.
inline Eigen::Vector3f VoxelCentre(const VoxelKey& voxel, float voxel_size_m) {
  return (voxel.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * voxel_size_m;
}

}  // namespace hylo
