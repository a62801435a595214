#pragma once
// The simulated high-voltage substation: ~120 m x 80 m of rough ground (site frame = map
// frame, x east, y north, z up, the fenced site spans [0, 120] x [0, 80]) with a switchyard
// of lattice gantries, busbars, insulator columns and transformers, a control building, a
// perimeter fence, cable trenches, and a raised annex with steep banks reached by one ramp.
//
// Two sessions of the same site: A (mapping) drives the lanes around and through the yard;
// B (localization) sees a changed site (a parked van and a container added, a fence segment
// removed, a cable drum moved) and climbs into the annex, which A never enters and whose
// ground lies 2.5 m up behind steep banks: A sees its bank faces and tall objects, but its
// plateau ground only in sparse grazing returns near the bank edges (seed 1: ~0.05 % of A's
// returns).

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hylo/sim/primitives.h"
#include "hylo/sim/terrain.h"

namespace hylo::sim {

enum class SessionId { kA, kB };
/// "a" or "b".
std::string ToString(SessionId session);

/// One thing on the site, present in session A, in session B, or in both.
struct SiteObject {
  std::string kind;  ///< "gantry", "transformer", "fence", "container", ...
  bool in_a = true, in_b = true;
  std::vector<Primitive> parts;
};

struct Site {
  std::shared_ptr<const Terrain> terrain;
  std::vector<SiteObject> objects;
  std::vector<Eigen::Vector2d> route_a;                    ///< session A waypoints on the ground, m
  std::vector<Eigen::Vector2d> route_b;                    ///< session B waypoints, m
  Eigen::Vector2d site_min_m = Eigen::Vector2d(0.0, 0.0);  ///< fenced site corner, m
  Eigen::Vector2d site_max_m = Eigen::Vector2d(120.0, 80.0);  ///< opposite corner, m
  Eigen::Vector2d annex_min_m = Eigen::Vector2d::Zero();      ///< area only B visits, m
  Eigen::Vector2d annex_max_m = Eigen::Vector2d::Zero();
};

/// Builds the site. The layout (lanes, bays, annex) is fixed so that the routes stay
/// collision-free; the seed varies the ground (undulation phases, hill shapes, gravel),
/// small placement offsets of the objects and the transformers' orientation by 180 deg.
Site BuildSite(uint64_t seed, const TerrainOptions& terrain_options);

/// The primitives present in `session`, each with `object_id` = index into site.objects.
std::vector<Primitive> SessionPrimitives(const Site& site, SessionId session);

}  // namespace hylo::sim
