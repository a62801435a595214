#include "hylo/inspection/ray_caster.h"

namespace hylo::inspection {

bool SegmentBlocked(const OccupancyGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return WalkVoxels(grid, a, b, [&grid](const Eigen::Vector3i& voxel) {
    return grid.TestBit(grid.LinearIndex(voxel));
  });
}

}  // namespace hylo::inspection
