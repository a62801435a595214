// 2-D DDA grid walk and the per-cell primitive lists.
#include "hylo/sim/spatial_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hylo/common/check.h"

namespace hylo::sim {
namespace {
constexpr double kTiny = 1e-12;

// Clips the ray's ground projection to the grid rectangle (2-D slab test).
bool ClipToGrid(const Grid2d& grid, const Ray& ray, double* t_start, double* t_end) {
  const Eigen::Vector2d lo = grid.origin_m, hi = grid.Max();
  for (int i = 0; i < 2; ++i) {
    const double o = ray.origin[i], d = ray.direction[i];
    if (std::abs(d) < kTiny) {
      if (o < lo[i] || o >= hi[i]) return false;
      continue;
    }
    double t0 = (lo[i] - o) / d, t1 = (hi[i] - o) / d;
    if (t0 > t1) std::swap(t0, t1);
    *t_start = std::max(*t_start, t0);
    *t_end = std::min(*t_end, t1);
  }
  return *t_start < *t_end;
}
}  // namespace

GridWalk2d::GridWalk2d(const Grid2d& grid, const Ray& ray, double t_start, double t_end)
    : nx_(grid.nx), ny_(grid.ny), t_(t_start), t_end_(t_end) {
  if (!ClipToGrid(grid, ray, &t_, &t_end_)) {
    done_ = true;
    return;
  }
  const Eigen::Vector2d start =
      (ray.origin.head<2>() + t_ * ray.direction.head<2>() - grid.origin_m) / grid.cell_m;
  ix_ = std::clamp(static_cast<int>(std::floor(start.x())), 0, nx_ - 1);
  iy_ = std::clamp(static_cast<int>(std::floor(start.y())), 0, ny_ - 1);
  const double dx = ray.direction.x(), dy = ray.direction.y();
  if (std::abs(dx) > kTiny) {
    step_x_ = dx > 0 ? 1 : -1;
    const double edge = grid.origin_m.x() + grid.cell_m * (ix_ + (dx > 0 ? 1 : 0));
    t_next_x_ = (edge - ray.origin.x()) / dx;
    t_delta_x_ = grid.cell_m / std::abs(dx);
  }
  if (std::abs(dy) > kTiny) {
    step_y_ = dy > 0 ? 1 : -1;
    const double edge = grid.origin_m.y() + grid.cell_m * (iy_ + (dy > 0 ? 1 : 0));
    t_next_y_ = (edge - ray.origin.y()) / dy;
    t_delta_y_ = grid.cell_m / std::abs(dy);
  }
}

bool GridWalk2d::Next(int* ix, int* iy, double* t_enter, double* t_exit) {
  if (done_) return false;
  *ix = ix_;
  *iy = iy_;
  *t_enter = t_;
  const double t_cross = std::min(t_next_x_, t_next_y_);
  *t_exit = std::min(std::max(t_cross, t_), t_end_);
  if (t_cross >= t_end_) {
    done_ = true;
    return true;
  }
  if (t_next_x_ < t_next_y_) {
    ix_ += step_x_;
    t_next_x_ += t_delta_x_;
  } else {
    iy_ += step_y_;
    t_next_y_ += t_delta_y_;
  }
  t_ = *t_exit;
  if (ix_ < 0 || ix_ >= nx_ || iy_ < 0 || iy_ >= ny_) done_ = true;
  return true;
}

PrimitiveGrid::PrimitiveGrid(const Grid2d& grid, const std::vector<Primitive>& primitives)
    : grid_(grid) {
  HYLO_CHECK(grid.nx > 0 && grid.ny > 0 && grid.cell_m > 0.0, "empty grid");
  const int cells = grid.nx * grid.ny;
  std::vector<std::vector<int32_t>> lists(cells);
  top_z_.assign(cells, -std::numeric_limits<double>::infinity());
  for (int32_t id = 0; id < static_cast<int32_t>(primitives.size()); ++id) {
    const Aabb box = BoundsOf(primitives[id]);
    const auto cell_of = [&](double v, double o, int n) {
      return std::clamp(static_cast<int>(std::floor((v - o) / grid.cell_m)), 0, n - 1);
    };
    const int x0 = cell_of(box.min.x(), grid.origin_m.x(), grid.nx);
    const int x1 = cell_of(box.max.x(), grid.origin_m.x(), grid.nx);
    const int y0 = cell_of(box.min.y(), grid.origin_m.y(), grid.ny);
    const int y1 = cell_of(box.max.y(), grid.origin_m.y(), grid.ny);
    for (int iy = y0; iy <= y1; ++iy) {
      for (int ix = x0; ix <= x1; ++ix) {
        lists[grid.Index(ix, iy)].push_back(id);
        top_z_[grid.Index(ix, iy)] = std::max(top_z_[grid.Index(ix, iy)], box.max.z());
      }
    }
  }
  offsets_.assign(cells + 1, 0);
  for (int c = 0; c < cells; ++c) offsets_[c + 1] = offsets_[c] + lists[c].size();
  ids_.reserve(offsets_.back());
  for (const auto& list : lists) ids_.insert(ids_.end(), list.begin(), list.end());
}

}  // namespace hylo::sim
