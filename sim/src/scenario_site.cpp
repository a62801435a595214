// A scenario's site: the terrain (hills, bumps on the lanes, trenches, undulation, a hill
// under the start), the fence with its gates, equipment in a share of the bays, and
// vegetation-like clutter off the roads (none near an empty spur).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>

#include "hylo/sim/scenario.h"
#include "route.h"
#include "scenario_lanes.h"
#include "scenario_objects.h"

namespace hylo::sim {
namespace {

using scenario_site::Drives;
using scenario_site::LaneGrid;
using scenario_site::V2;

constexpr double kDeg = M_PI / 180.0;
constexpr double kStartHillSigmaM = 5.0;
constexpr double kTerrainMarginM = 40.0;  // ground beyond everything the drives reach, m
constexpr double kGateWidthM = 6.0;

// Gaussian hill whose flank at distance sigma from its top has the recipe's start slope
// (max slope of h exp(-r^2 / 2 sigma^2) is 0.607 h / sigma, at r = sigma).
Hill StartHill(const SiteRecipe& recipe, const Drives& drives, double angle_rad) {
  Hill hill;
  hill.sigma_m = kStartHillSigmaM;
  hill.height_m = std::tan(recipe.start_slope_deg * kDeg) * hill.sigma_m / 0.607;
  hill.center_m = drives.start + hill.sigma_m * V2(std::cos(angle_rad), std::sin(angle_rad));
  return hill;
}

TerrainShape MakeShape(const SiteRecipe& recipe, const LaneGrid& lanes, const Drives& drives,
                       Rng* rng) {
  TerrainShape shape;
  const V2 yard = recipe.yard_size_m;
  const double start_angle = rng->Uniform(0.0, 2.0 * M_PI);
  if (recipe.start_slope_deg > 0.0) shape.hills.push_back(StartHill(recipe, drives, start_angle));
  for (int k = 0; k < recipe.hills; ++k) {
    Hill hill;
    hill.center_m = V2(rng->Uniform(0.0, yard.x()), rng->Uniform(0.0, yard.y()));
    hill.sigma_m = rng->Uniform(4.0, 10.0);
    hill.height_m = (rng->Uniform() < 0.5 ? -1.0 : 1.0) * hill.sigma_m * rng->Uniform(0.1, 0.4);
    shape.hills.push_back(hill);
  }
  for (int k = 0; k < recipe.bumps; ++k) {  // on a random lane
    const bool along_x = rng->Uniform() < 0.5;
    const double across = along_x ? lanes.ys[static_cast<std::size_t>(rng->Uniform() * lanes.ny())]
                                  : lanes.xs[static_cast<std::size_t>(rng->Uniform() * lanes.nx())];
    const double along = along_x ? rng->Uniform(lanes.xs.front(), lanes.xs.back())
                                 : rng->Uniform(lanes.ys.front(), lanes.ys.back());
    Hill bump;
    bump.center_m = along_x ? V2(along, across) : V2(across, along);
    bump.height_m = rng->Uniform(0.05, 0.25);
    bump.sigma_m = rng->Uniform(0.4, 1.2);
    shape.hills.push_back(bump);
  }
  for (int k = 0; k < recipe.trenches; ++k) {  // cable trenches follow the rows
    Trench trench;
    trench.start_m = V2(rng->Uniform(0.0, yard.x()), rng->Uniform(0.0, yard.y()));
    const double length = rng->Uniform(10.0, 40.0);
    trench.end_m = trench.start_m + (rng->Uniform() < 0.5 ? V2(length, 0.0) : V2(0.0, length));
    trench.width_m = rng->Uniform(0.4, 0.8);
    trench.depth_m = rng->Uniform(0.3, 0.6);
    shape.trenches.push_back(trench);
  }
  shape.undulation_m = recipe.undulation_m;
  shape.undulation_wavelength_m = recipe.undulation_wavelength_m;
  shape.undulation_phase = V2(rng->Uniform(0.0, 2.0 * M_PI), rng->Uniform(0.0, 2.0 * M_PI));
  return shape;
}

TerrainOptions TerrainExtent(const Scenario& scenario, const Drives& drives) {
  TerrainOptions options;
  V2 lo = V2::Zero(), hi = scenario.site.yard_size_m;
  for (const auto* route : {&drives.route_a, &drives.route_b}) {
    for (const V2& p : *route) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  options.min_m = lo - V2::Constant(kTerrainMarginM);
  options.max_m = hi + V2::Constant(kTerrainMarginM);
  options.resolution_m = scenario.terrain_resolution_m;
  options.gravel_sigma_m = scenario.site.gravel_sigma_m;
  return options;
}

// The fence around the yard, open where a road leaves it.
void AddPerimeter(const Scenario& scenario, const Drives& drives, scenario_site::Objects* objects) {
  const V2 size = scenario.site.yard_size_m;
  const V2 corners[4] = {V2(0, 0), V2(size.x(), 0), size, V2(0, size.y())};
  for (int side = 0; side < 4; ++side) {
    const V2 a = corners[side], b = corners[(side + 1) % 4];
    const double length = (b - a).norm();
    const V2 dir = (b - a) / length;
    std::vector<std::pair<double, double>> gaps;  // along the side, m
    for (const auto& gate : drives.gates) {
      if (scenario_site::DistanceToSegment(gate.fence_point, a, b) > 1e-6) continue;
      const double s = (gate.fence_point - a).dot(dir);
      gaps.push_back({s - 0.5 * kGateWidthM, s + 0.5 * kGateWidthM});
    }
    std::sort(gaps.begin(), gaps.end());
    double from = 0.0;
    gaps.push_back({length, length});
    for (const auto& [gap_start, gap_end] : gaps) {
      if (gap_start - from > 1.0) objects->Fence(a + from * dir, a + gap_start * dir);
      from = std::max(from, gap_end);
    }
  }
}

}  // namespace

Site BuildScenarioSite(const Scenario& scenario) {
  const SiteRecipe& recipe = scenario.site;
  Rng rng = Rng::Derive(scenario.number, 0x517e5ce7);
  const LaneGrid lanes = scenario_site::MakeLaneGrid(recipe);
  const Drives drives =
      scenario_site::PlanDrives(recipe, lanes, &rng, [&](const std::vector<V2>& route_a) {
        const RoutePlan plan(route_a, scenario.trajectory);
        V2 xy;
        double heading = 0.0, speed = 0.0, distance_m = 0.0;
        plan.Sample(std::min(plan.duration_s(), scenario.max_drive_a_s), &xy, &heading, &speed,
                    &distance_m);
        return distance_m;
      });
  Site site;
  site.terrain = std::make_shared<const Terrain>(MakeShape(recipe, lanes, drives, &rng),
                                                 TerrainExtent(scenario, drives),
                                                 Rng::Derive(scenario.number, 0x7e44).NextU64());
  site.route_a = drives.route_a;
  site.route_b = drives.route_b;
  site.site_min_m = V2::Zero();
  site.site_max_m = recipe.yard_size_m;
  scenario_site::Objects objects(&site, &rng);
  AddPerimeter(scenario, drives, &objects);
  objects.Equipment(recipe, lanes);
  objects.Clutter(recipe, lanes, drives);
  return site;
}

}  // namespace hylo::sim
