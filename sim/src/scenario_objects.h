#pragma once
// What stands on a scenario's site: the fence, equipment in the bays between the lanes, and
// vegetation-like clutter (bushes and trees of small, randomly turned boxes and twigs).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hylo/sim/random.h"
#include "hylo/sim/scenario.h"
#include "scenario_lanes.h"
#include "site_structures.h"

namespace hylo::sim::scenario_site {

class Objects {
 public:
  /// Adds to `site` (its terrain must be set); draws from `rng`.
  Objects(Site* site, Rng* rng) : site_(site), rng_(rng) {}

  /// A fence run from a to b (posts and mesh panels).
  void Fence(const V2& a, const V2& b);
  /// Equipment in a share (structure_density) of the bays between the lanes.
  void Equipment(const SiteRecipe& recipe, const LaneGrid& lanes);
  /// Bushes and trees off the lanes, roads and equipment; none within 30 m of an empty spur.
  /// A share (changed_fraction) is present in only one of the sessions.
  void Clutter(const SiteRecipe& recipe, const LaneGrid& lanes, const Drives& drives);

 private:
  struct Box2 {
    V2 min, max;
  };
  double Ground(const V2& xy, double radius) const;
  /// A new object's parts; the pointer is good until the next Add (the list grows).
  structures::Parts* Add(const std::string& kind, bool in_a = true, bool in_b = true);
  void Bay(const Box2& bay);
  void Gantry(const V2& center, const V2& axis, double span_m);
  void Bush(const V2& xy, bool in_a, bool in_b);
  void Tree(const V2& xy, bool in_a, bool in_b);
  bool ClearOfEverything(const V2& p, const LaneGrid& lanes, const Drives& drives, bool spur) const;
  Eigen::Matrix3d RandomRotation();
  Eigen::Vector3d RandomUnit();

  Site* site_;
  Rng* rng_;
  std::vector<Box2> occupied_;  // bays with equipment
};

}  // namespace hylo::sim::scenario_site
