#include "hylo/sim/surface_distance.h"

#include <algorithm>
#include <cmath>

#include "hylo/common/check.h"

namespace hylo::sim {
namespace {

// A grid of `cell_m` cells over the terrain's extent (primitives beyond it are clamped into
// the border cells by PrimitiveGrid, and so are queries).
Grid2d GridOver(const Terrain& terrain, double cell_m) {
  HYLO_CHECK(cell_m > 0.0, "cell_m must be > 0");
  Grid2d grid;
  grid.origin_m = terrain.options().min_m;
  grid.cell_m = cell_m;
  const Eigen::Vector2d extent = terrain.options().max_m - terrain.options().min_m;
  grid.nx = std::max(1, static_cast<int>(std::ceil(extent.x() / cell_m)));
  grid.ny = std::max(1, static_cast<int>(std::ceil(extent.y() / cell_m)));
  return grid;
}

}  // namespace

SurfaceDistanceField::SurfaceDistanceField(const World& world, double cell_m)
    : world_(world), index_(GridOver(world.terrain(), cell_m), world.primitives()) {}

SurfaceDistance SurfaceDistanceField::Nearest(const Eigen::Vector3d& point_map) const {
  const Terrain& terrain = world_.terrain();
  SurfaceDistance nearest;
  // Ground: distance to the tangent plane of the height field under the point.
  const double n_z = terrain.Normal(point_map.x(), point_map.y()).z();
  nearest.distance_m = std::abs(point_map.z() - terrain.Height(point_map.x(), point_map.y())) * n_z;
  nearest.primitive = -1;
  const Grid2d& grid = index_.grid();
  const Eigen::Vector2d g = (point_map.head<2>() - grid.origin_m) / grid.cell_m;
  const int cx = std::clamp(static_cast<int>(std::floor(g.x())), 0, grid.nx - 1);
  const int cy = std::clamp(static_cast<int>(std::floor(g.y())), 0, grid.ny - 1);
  const std::vector<Primitive>& primitives = world_.primitives();
  for (int iy = std::max(0, cy - 1); iy <= std::min(grid.ny - 1, cy + 1); ++iy) {
    for (int ix = std::max(0, cx - 1); ix <= std::min(grid.nx - 1, cx + 1); ++ix) {
      const int cell = grid.Index(ix, iy);
      for (const int32_t* id = index_.Begin(cell); id != index_.End(cell); ++id) {
        const double d = std::abs(SignedDistance(primitives[*id], point_map));
        if (d < nearest.distance_m) nearest = {d, *id};
      }
    }
  }
  return nearest;
}

}  // namespace hylo::sim
