#pragma once
// Slope post-processing (Zhang et al. 2016, Sec. 2.3): on steep terrain a rigid cloth stays
// above the ground between pinned particles, so ground points there would be called objects.
// Movable particles next to pinned ones whose surface height continues the pinned neighbour's
// height (within a threshold) are terrain, not a gap under an object: they are put on the
// surface and pinned, and the correction spreads from them. A particle is only pinned where the
// cloth already lies close above the surface (the reference code's second test, there switched
// off with a 9999 m threshold): a rigid cloth floats a few metres above a slope, but it spans
// a bridge deck by its full height, and a deck joins the road at its ends without a step, so
// the height test alone walks onto it (ISPRS samp21).

#include <cstddef>
#include <vector>

#include "hylo/terrain/cloth_filter_cloth.h"

namespace hylo::terrain::cloth {

/// Pins movable particles reachable from pinned ones through 4-neighbour steps of less than
/// `height_threshold_m` in surface height, where the settled cloth is less than
/// `max_cloth_gap_m` above the surface under the particle. Only movable regions (4-connected)
/// of more than `min_region_particles` particles are corrected: a small region is a small object
/// the cloth rightly spans (a car, a shed), not a slope. Returns the number of particles pinned.
std::size_t SmoothSteepSlopes(const std::vector<double>& surface_height_m,
                              double height_threshold_m, double max_cloth_gap_m,
                              std::size_t min_region_particles, Cloth* cloth);

}  // namespace hylo::terrain::cloth
