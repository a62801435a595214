#pragma once
// Spatial index for ray casting: a uniform 2-D grid over the site (z up, so a ground
// vehicle's rays cross few cells), walked cell by cell along the ray's ground projection
// (Amanatides & Woo 1987, "A fast voxel traversal algorithm").

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "hylo/sim/primitives.h"

namespace hylo::sim {

/// The geometry of a uniform 2-D grid: cell (ix, iy) covers
/// [origin + ix * cell, origin + (ix + 1) * cell) in x and likewise in y.
struct Grid2d {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  ///< lower-left corner, map frame, m
  double cell_m = 1.0;                                 ///< cell edge, m
  int nx = 0, ny = 0;                                  ///< cells along x and y
  int Index(int ix, int iy) const { return iy * nx + ix; }
  Eigen::Vector2d Max() const { return origin_m + cell_m * Eigen::Vector2d(nx, ny); }
};

/// Visits the cells a ray crosses between t_start and t_end, in order of distance.
class GridWalk2d {
 public:
  GridWalk2d(const Grid2d& grid, const Ray& ray, double t_start, double t_end);
  /// Next cell and the ray interval [t_enter, t_exit] inside it; false when done.
  bool Next(int* ix, int* iy, double* t_enter, double* t_exit);

 private:
  int ix_ = 0, iy_ = 0, step_x_ = 0, step_y_ = 0, nx_ = 0, ny_ = 0;
  double t_ = 0.0, t_end_ = 0.0;
  double t_next_x_ = 1e300, t_next_y_ = 1e300, t_delta_x_ = 1e300, t_delta_y_ = 1e300;
  bool done_ = false;
};

/// Primitive indices per 2-D cell (their xy bounding box overlaps the cell), stored flat.
class PrimitiveGrid {
 public:
  PrimitiveGrid() = default;
  PrimitiveGrid(const Grid2d& grid, const std::vector<Primitive>& primitives);

  const Grid2d& grid() const { return grid_; }
  /// Indices of the primitives overlapping cell `cell_index` as [begin, end).
  const int32_t* Begin(int cell_index) const { return ids_.data() + offsets_[cell_index]; }
  const int32_t* End(int cell_index) const { return ids_.data() + offsets_[cell_index + 1]; }
  /// Highest primitive point in the cell (-inf when empty), m.
  double TopZ(int cell_index) const { return top_z_[cell_index]; }

 private:
  Grid2d grid_;
  std::vector<int32_t> offsets_;  // size nx*ny + 1
  std::vector<int32_t> ids_;
  std::vector<double> top_z_;
};

}  // namespace hylo::sim
