#include "hylo/inspection/ray_caster.h"

namespace hylo::inspection {

bool SegmentBlocked(const OccupancyGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d q0 = grid.ToVoxelCoordinates(a);
  const Eigen::Vector3d d = grid.ToVoxelCoordinates(b) - q0;
  constexpr double kPerBrick = 1.0 / OccupancyGrid::kBrick;
  // A parameter slack at brick faces (in voxels: 1e-6) so that rounding cannot skip a voxel a
  // face passes through; the extra voxel it may visit is one the segment touches anyway.
  const double slack = 1e-6 / std::max(1.0, d.norm());
  return WalkLattice(
      grid.brick_dims(), q0 * kPerBrick, d * kPerBrick, 0.0, 1.0,
      [&](const Eigen::Vector3i& brick, double t_in, double t_out) {
        if (!grid.BrickBlocked(brick)) return false;
        return WalkLattice(grid.dims(), q0, d, std::max(0.0, t_in - slack),
                           std::min(1.0, t_out + slack),
                           [&grid](const Eigen::Vector3i& voxel, double, double) {
                             return grid.TestBit(grid.LinearIndex(voxel));
                           });
      });
}

}  // namespace hylo::inspection
