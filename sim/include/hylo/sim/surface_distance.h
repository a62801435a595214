#pragma once
// Distance from any point to the simulated site's true (noise-free) surfaces: the ray-cast
// terrain and every primitive of one session's world. Used to measure how thick a map is
// (RMS distance of its points to the truth) and which surface a map point belongs to,
// without going through a sampled reference cloud.

#include <Eigen/Core>
#include <cstdint>

#include "hylo/sim/spatial_index.h"
#include "hylo/sim/world.h"

namespace hylo::sim {

/// The nearest true surface of a point.
struct SurfaceDistance {
  double distance_m = 0.0;  ///< unsigned distance to the nearest surface, m
  int32_t primitive = -1;   ///< World primitive index, -1 = the ground
  bool IsGround() const { return primitive < 0; }
};

/// Answers nearest-surface queries on a World (kept by reference: it must outlive this).
/// Primitives: exact distance (SignedDistance). Ground: |z - h(x, y)| * n_z, the distance to
/// the tangent plane of the ray-cast height field at (x, y); exact on a planar patch, off by
/// a second-order term where the ground bends within the distance (gravel, trench edges).
/// Primitives are found through a 2-D grid of `cell_m` cells, looking at the 3 x 3 cells
/// around the query: every primitive within `cell_m` horizontally is tested, so distances
/// below `cell_m` are exact; a farther primitive may be missed (the ground is always tested).
class SurfaceDistanceField {
 public:
  explicit SurfaceDistanceField(const World& world, double cell_m = 2.0);

  /// Nearest surface of `point_map`. Thread-safe (no mutable state).
  SurfaceDistance Nearest(const Eigen::Vector3d& point_map) const;

 private:
  const World& world_;
  PrimitiveGrid index_;
};

}  // namespace hylo::sim
