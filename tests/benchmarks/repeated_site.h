#pragma once
// The simulated substation repeated over about a square kilometre, for the tiled map
// benchmark: one world (terrain + every copy's structures) from which both the synthetic prior
// map (surfaces sampled directly, > 100 M points) and a simulated drive are made, so the map
// and the scans agree wherever the drive goes.
//
// Copies sit on a grid whose period is a whole number of the terrain undulation's wavelengths
// (23 m along x, 28.75 m along y), so every copy stands on the ground it was built on. The
// annex (a raised quadrant in the original terrain) is left out: a quadrant repeated would
// stack. Between the copies' fences run 18 m roads; the drive follows one of them north.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/sim/site_layout.h"

namespace hylo::benchmarks {

struct RepeatedSiteOptions {
  int copies_x = 8;                                          ///< copies along x
  int copies_y = 9;                                          ///< copies along y
  Eigen::Vector2d period_m = Eigen::Vector2d(138.0, 115.0);  ///< copy spacing, m
  double terrain_resolution_m = 0.4;  ///< ray-cast ground grid, m (the Fast simulator's)
};

/// The repeated site: terrain over every copy, each copy's objects (session A and B flags kept),
/// site_min/max spanning the whole, and route_b = `route_m`.
sim::Site RepeatedSite(const sim::Site& base, const RepeatedSiteOptions& options,
                       const std::vector<Eigen::Vector2d>& route_m, uint64_t seed);

/// x of the road between copy columns `column` and `column + 1`, m.
double RoadX(const RepeatedSiteOptions& options, int column);

/// What WriteSiteMap wrote.
struct SiteMapSummary {
  std::size_t ground_points = 0;
  std::size_t object_points = 0;
};

/// The prior map of session A's world: the ground sampled every `ground_spacing_m` (cell
/// centres, points inside a structure left out) and the structures' surfaces at about one
/// point per `object_spacing_m`^2 (sim::ReferenceCloud, band by band), streamed to a binary
/// PCD (float32 x y z, the site frame). Memory: one band of object points.
SiteMapSummary WriteSiteMap(const sim::Site& site, const std::string& path, double ground_spacing_m,
                            double object_spacing_m, uint64_t seed);

}  // namespace hylo::benchmarks
