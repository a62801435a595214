// Ray casting through the index: one 2-D walk over coarse cells; in each cell the ray is
// tested against the primitives listed there and, where it comes low enough, the ground.
#include "hylo/sim/world.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "hylo/common/check.h"

namespace hylo::sim {
namespace {
constexpr double kSelfHitEps = 1e-9;  // m: ignore crossings at the ray origin itself

// Remembers the last few primitives tested by one ray: long primitives (busbars, fences)
// span many cells and would otherwise be re-tested in each.
class RecentIds {
 public:
  bool SeenOrAdd(int32_t id) {
    for (const int32_t seen : ids_) {
      if (seen == id) return true;
    }
    ids_[next_] = id;
    next_ = (next_ + 1) % ids_.size();
    return false;
  }

 private:
  std::array<int32_t, 16> ids_{-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
  size_t next_ = 0;
};

// Does the ray cross the box for some t in [0, t_max]? (slab test, inv_dir = 1 / direction)
bool CrossesBox(const Aabb& box, const Ray& ray, const Eigen::Vector3d& inv_dir, double t_max) {
  double t_lo = 0.0, t_hi = t_max;
  for (int i = 0; i < 3; ++i) {
    double t0 = (box.min[i] - ray.origin[i]) * inv_dir[i];
    double t1 = (box.max[i] - ray.origin[i]) * inv_dir[i];
    if (t0 > t1) std::swap(t0, t1);
    // NaN (0 * inf on a face) compares false and leaves the interval unchanged: conservative.
    if (t0 > t_lo) t_lo = t0;
    if (t1 < t_hi) t_hi = t1;
    if (t_lo > t_hi) return false;
  }
  return true;
}
// Walks the ground cells along one ray, resuming where it stopped when consecutive index
// cells need the ground, restarting when cells high above the ground were skipped.
class GroundWalk {
 public:
  GroundWalk(const Terrain& terrain, const Ray& ray, double t_max)
      : terrain_(terrain), ray_(ray), t_max_(t_max) {}

  bool Intersect(double t0, double t1, SurfaceHit* hit) {
    if (!walk_ || next_t_ < t0 - 1e-9) {
      walk_.emplace(terrain_.cells(), ray_, t0, t_max_);
      pending_ = walk_->Next(&ix_, &iy_, &te_, &tx_);
      next_t_ = t0;
    }
    while (pending_ && te_ < t1) {
      const bool found = terrain_.IntersectCell(ray_, ix_, iy_, te_, tx_, hit);
      next_t_ = tx_;
      pending_ = walk_->Next(&ix_, &iy_, &te_, &tx_);
      if (found) return true;
    }
    return false;
  }

 private:
  const Terrain& terrain_;
  const Ray& ray_;
  double t_max_;
  std::optional<GridWalk2d> walk_;
  bool pending_ = false;
  int ix_ = 0, iy_ = 0;
  double te_ = 0.0, tx_ = 0.0, next_t_ = 0.0;
};

}  // namespace

World::World(std::shared_ptr<const Terrain> terrain, std::vector<Primitive> primitives,
             double index_cell_m)
    : terrain_(std::move(terrain)), primitives_(std::move(primitives)) {
  HYLO_CHECK(terrain_ != nullptr && index_cell_m > 0.0, "terrain and cell size");
  const TerrainOptions& t = terrain_->options();
  Grid2d grid;
  grid.origin_m = t.min_m;
  grid.cell_m = index_cell_m;
  grid.nx = static_cast<int>(std::ceil((t.max_m.x() - t.min_m.x()) / index_cell_m));
  grid.ny = static_cast<int>(std::ceil((t.max_m.y() - t.min_m.y()) / index_cell_m));
  index_ = PrimitiveGrid(grid, primitives_);
  for (const Primitive& p : primitives_) bounds_.push_back(BoundsOf(p));
  cell_ground_top_.resize(static_cast<size_t>(grid.nx) * grid.ny);
  top_z_ = terrain_->max_height_m();
  for (int iy = 0; iy < grid.ny; ++iy) {
    for (int ix = 0; ix < grid.nx; ++ix) {
      const Eigen::Vector2d lo = grid.origin_m + index_cell_m * Eigen::Vector2d(ix, iy);
      const int c = grid.Index(ix, iy);
      cell_ground_top_[c] = terrain_->MaxHeightIn(lo, lo + Eigen::Vector2d::Constant(index_cell_m));
      top_z_ = std::max(top_z_, index_.TopZ(c));
    }
  }
}

bool World::InsideAnyPrimitive(const Eigen::Vector3d& point_map, double margin_m,
                               int32_t ignore) const {
  const Grid2d& grid = index_.grid();
  const Eigen::Vector2d g = (point_map.head<2>() - grid.origin_m) / grid.cell_m;
  const int ix = static_cast<int>(std::floor(g.x())), iy = static_cast<int>(std::floor(g.y()));
  if (ix < 0 || iy < 0 || ix >= grid.nx || iy >= grid.ny) return false;
  const int cell = grid.Index(ix, iy);
  for (const int32_t* id = index_.Begin(cell); id != index_.End(cell); ++id) {
    if (*id != ignore && SignedDistance(primitives_[*id], point_map) < -margin_m) return true;
  }
  return false;
}

bool World::Raycast(const Ray& ray, double max_range_m, RayHit* hit) const {
  double best_t = max_range_m;
  SurfaceHit best;
  int32_t best_id = -2;  // -2 nothing, -1 ground, >= 0 primitive
  RecentIds tested;
  GroundWalk ground(*terrain_, ray, max_range_m);
  const Eigen::Vector3d inv_dir = ray.direction.cwiseInverse();
  GridWalk2d walk(index_.grid(), ray, 0.0, max_range_m);
  int ix = 0, iy = 0;
  double t0 = 0.0, t1 = 0.0;
  while (walk.Next(&ix, &iy, &t0, &t1)) {
    if (t0 >= best_t) break;
    const double z0 = ray.origin.z() + t0 * ray.direction.z();
    if (ray.direction.z() > 0.0 && z0 > top_z_) break;  // climbing above everything
    const double z_low = std::min(z0, ray.origin.z() + t1 * ray.direction.z());
    const int cell = index_.grid().Index(ix, iy);
    SurfaceHit candidate;
    if (z_low <= index_.TopZ(cell)) {
      for (const int32_t* id = index_.Begin(cell); id != index_.End(cell); ++id) {
        if (tested.SeenOrAdd(*id) || !CrossesBox(bounds_[*id], ray, inv_dir, best_t)) continue;
        if (Intersect(primitives_[*id], ray, kSelfHitEps, best_t, &candidate)) {
          best_t = candidate.t;
          best = candidate;
          best_id = *id;
        }
      }
    }
    if (z_low <= cell_ground_top_[cell] && t0 < best_t &&
        ground.Intersect(t0, std::min(t1, best_t), &candidate) && candidate.t < best_t) {
      best_t = candidate.t;
      best = candidate;
      best_id = -1;
    }
  }
  if (best_id == -2) return false;
  hit->range_m = best_t;
  hit->point_map = ray.origin + best_t * ray.direction;
  hit->normal_map = best.normal_map;
  hit->primitive = best_id;
  hit->reflectivity =
      best_id >= 0 ? primitives_[best_id].reflectivity : terrain_->options().reflectivity;
  return true;
}

}  // namespace hylo::sim
