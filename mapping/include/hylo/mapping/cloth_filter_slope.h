#pragma once
// Slope post-processing (Zhang et al. 2016, Sec. 2.3): on steep terrain a rigid cloth stays
// above the ground between pinned particles, so ground points there would be called objects.
// Movable particles next to pinned ones whose surface height continues the pinned neighbour's
// height (within a threshold) are terrain, not a gap under an object: they are put on the
// surface and pinned, and the correction spreads from them.

#include <cstddef>
#include <vector>

#include "hylo/mapping/cloth_filter_cloth.h"

namespace hylo::mapping::cloth {

/// Pins movable particles reachable from pinned ones through 4-neighbour steps of less than
/// `height_threshold_m` in surface height. Only movable regions (4-connected) of more than
/// `min_region_particles` particles are corrected: a small region is a small object the cloth
/// rightly spans (a car, a shed), not a slope. Returns the number of particles pinned.
std::size_t SmoothSteepSlopes(const std::vector<double>& surface_height_m,
                              double height_threshold_m, std::size_t min_region_particles,
                              Cloth* cloth);

}  // namespace hylo::mapping::cloth
