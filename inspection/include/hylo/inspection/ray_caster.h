#pragma once
// Sight lines through the occupancy grid: the voxels a segment passes through, in order, by
// the 3-D digital differential analyser of Amanatides & Woo ("A Fast Voxel Traversal
// Algorithm for Ray Tracing", Eurographics 1987): from the voxel holding the start, step
// across whichever voxel face the segment reaches first (the smallest tMax), each step one
// face, until the end. Every voxel the segment's interior crosses is visited once; a segment
// that only touches an edge or corner of a voxel (a set of measure zero) may or may not
// visit it.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "hylo/inspection/occupancy_grid.h"

namespace hylo::inspection {

/// Calls `visit(voxel)` for each voxel of `grid` the segment from `a` to `b` (local frame)
/// crosses, from `a` on; the part outside the grid is skipped. Stops and returns true as soon
/// as `visit` returns true; false when it never did.
template <class Visit>
bool WalkVoxels(const OccupancyGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                Visit&& visit) {
  const Eigen::Vector3d q0 = grid.ToVoxelCoordinates(a);
  const Eigen::Vector3d d = grid.ToVoxelCoordinates(b) - q0;
  const Eigen::Vector3i& dims = grid.dims();
  // Clip the parameter range [0, 1] to the grid's box (slabs).
  double t_enter = 0.0, t_exit = 1.0;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (q0[i] < 0.0 || q0[i] >= dims[i]) return false;
      continue;
    }
    double t_low = (0.0 - q0[i]) / d[i], t_high = (dims[i] - q0[i]) / d[i];
    if (t_low > t_high) std::swap(t_low, t_high);
    t_enter = std::max(t_enter, t_low);
    t_exit = std::min(t_exit, t_high);
  }
  if (!(t_enter <= t_exit)) return false;
  const Eigen::Vector3d start = q0 + t_enter * d;
  Eigen::Vector3i voxel, step;
  Eigen::Vector3d t_max, t_delta;
  for (int i = 0; i < 3; ++i) {
    voxel[i] = std::clamp(static_cast<int>(std::floor(start[i])), 0, dims[i] - 1);
    step[i] = d[i] > 0.0 ? 1 : (d[i] < 0.0 ? -1 : 0);
    const double boundary = voxel[i] + (step[i] > 0 ? 1 : 0);
    t_max[i] = step[i] != 0 ? (boundary - q0[i]) / d[i] : std::numeric_limits<double>::infinity();
    t_delta[i] = step[i] != 0 ? 1.0 / std::abs(d[i]) : std::numeric_limits<double>::infinity();
  }
  while (true) {
    if (visit(static_cast<const Eigen::Vector3i&>(voxel))) return true;
    int axis = 0;
    if (t_max[1] < t_max[axis]) axis = 1;
    if (t_max[2] < t_max[axis]) axis = 2;
    if (t_max[axis] > t_exit) return false;
    voxel[axis] += step[axis];
    if (voxel[axis] < 0 || voxel[axis] >= dims[axis]) return false;
    t_max[axis] += t_delta[axis];
  }
}

/// True when the segment from `a` to `b` crosses a blocked voxel.
bool SegmentBlocked(const OccupancyGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace hylo::inspection
