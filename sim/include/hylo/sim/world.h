#pragma once
// The world one session sees: the terrain plus the site's primitives, with a 2-D grid
// index so that a ray tests only the primitives and ground cells along its path.

#include <memory>
#include <vector>

#include "hylo/sim/primitives.h"
#include "hylo/sim/spatial_index.h"
#include "hylo/sim/terrain.h"

namespace hylo::sim {

/// What a ray hit first.
struct RayHit {
  double range_m = 0.0;                                   ///< distance from the origin, m
  Eigen::Vector3d point_map = Eigen::Vector3d::Zero();    ///< hit point, map frame, m
  Eigen::Vector3d normal_map = Eigen::Vector3d::UnitZ();  ///< outward unit normal
  int32_t primitive = -1;    ///< index into World::primitives(), -1 = the ground
  float reflectivity = 0.f;  ///< of the surface hit
  bool IsGround() const { return primitive < 0; }
};

class World {
 public:
  /// `index_cell_m`: edge of the index cells (a few metres: few primitives per cell).
  World(std::shared_ptr<const Terrain> terrain, std::vector<Primitive> primitives,
        double index_cell_m = 2.0);

  /// First surface along the ray within (0, max_range_m]; false if nothing is hit.
  /// `ray.direction` must be of unit length. Thread-safe (no mutable state).
  bool Raycast(const Ray& ray, double max_range_m, RayHit* hit) const;

  /// True when `point_map` lies strictly inside a primitive (deeper than `margin_m`) other
  /// than `ignore` (index, or -1).
  bool InsideAnyPrimitive(const Eigen::Vector3d& point_map, double margin_m,
                          int32_t ignore = -1) const;

  const Terrain& terrain() const { return *terrain_; }
  const std::vector<Primitive>& primitives() const { return primitives_; }

 private:
  std::shared_ptr<const Terrain> terrain_;
  std::vector<Primitive> primitives_;
  std::vector<Aabb> bounds_;  // per primitive: a cheap slab test before the exact one
  PrimitiveGrid index_;
  std::vector<double> cell_ground_top_;  // highest ground vertex per index cell, m
  double top_z_ = 0.0;                   // highest point of anything, m
};

}  // namespace hylo::sim
