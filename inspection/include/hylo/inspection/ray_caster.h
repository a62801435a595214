#pragma once
// Sight lines through the occupancy grid: the voxels a segment passes through, in order, by
// the 3-D digital differential analyser of Amanatides & Woo ("A Fast Voxel Traversal
// Algorithm for Ray Tracing", Eurographics 1987): from the voxel holding the start, step
// across whichever voxel face the segment reaches first (the smallest tMax), each step one
// face, until the end. Every voxel the segment's interior crosses is visited once; a segment
// that only touches an edge or corner of a voxel (a set of measure zero) may or may not
// visit it.
//
// SegmentBlocked walks twice: first the grid's bricks (8^3 voxels, OccupancyGrid keeps which
// hold a blocked voxel), then the voxels only inside the bricks that do. Most of a sight line
// runs through empty air, so it crosses a brick in one step instead of eight or more.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "hylo/inspection/occupancy_grid.h"

namespace hylo::inspection {

/// The DDA on a lattice of unit cells [0, dims): the segment q0 + t d for t in [t0, t1]
/// (lattice coordinates). Calls visit(cell, t_in, t_out) for each cell crossed, in order,
/// with the parameter range the segment spends in it; stops and returns true as soon as visit
/// returns true.
template <class Visit>
bool WalkLattice(const Eigen::Vector3i& dims, const Eigen::Vector3d& q0, const Eigen::Vector3d& d,
                 double t0, double t1, Visit&& visit) {
  // Clip [t0, t1] to the lattice's box (slabs).
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (q0[i] < 0.0 || q0[i] >= dims[i]) return false;
      continue;
    }
    double t_low = (0.0 - q0[i]) / d[i], t_high = (dims[i] - q0[i]) / d[i];
    if (t_low > t_high) std::swap(t_low, t_high);
    t0 = std::max(t0, t_low);
    t1 = std::min(t1, t_high);
  }
  if (!(t0 <= t1)) return false;
  int cell[3], step[3];
  double t_max[3], t_delta[3];
  for (int i = 0; i < 3; ++i) {
    cell[i] = std::clamp(static_cast<int>(std::floor(q0[i] + t0 * d[i])), 0, dims[i] - 1);
    step[i] = d[i] > 0.0 ? 1 : (d[i] < 0.0 ? -1 : 0);
    const double boundary = cell[i] + (step[i] > 0 ? 1 : 0);
    t_max[i] = step[i] != 0 ? (boundary - q0[i]) / d[i] : std::numeric_limits<double>::infinity();
    t_delta[i] = step[i] != 0 ? 1.0 / std::abs(d[i]) : std::numeric_limits<double>::infinity();
  }
  double t_in = t0;
  while (true) {
    int axis = t_max[1] < t_max[0] ? 1 : 0;
    if (t_max[2] < t_max[axis]) axis = 2;
    const double t_out = std::min(t_max[axis], t1);
    if (visit(Eigen::Vector3i(cell[0], cell[1], cell[2]), t_in, t_out)) return true;
    if (t_max[axis] > t1) return false;
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= dims[axis]) return false;
    t_in = t_max[axis];
    t_max[axis] += t_delta[axis];
  }
}

/// Calls `visit(voxel)` for each voxel of `grid` the segment from `a` to `b` (local frame)
/// crosses, from `a` on; the part outside the grid is skipped. Stops and returns true as soon
/// as `visit` returns true; false when it never did.
template <class Visit>
bool WalkVoxels(const OccupancyGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                Visit&& visit) {
  const Eigen::Vector3d q0 = grid.ToVoxelCoordinates(a);
  return WalkLattice(grid.dims(), q0, grid.ToVoxelCoordinates(b) - q0, 0.0, 1.0,
                     [&visit](const Eigen::Vector3i& voxel, double, double) { return visit(voxel); });
}

/// True when the segment from `a` to `b` crosses a blocked voxel.
bool SegmentBlocked(const OccupancyGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace hylo::inspection
