#pragma once
// Site-level ground truth for evaluating maps, ground extraction and traversability:
// a noise-free reference cloud with ground/object labels, and the true slope on a grid.

#include <cstdint>
#include <string>

#include "hylo/io/cloud_io.h"
#include "hylo/sim/site_layout.h"
#include "hylo/sim/world.h"

namespace hylo::sim {

/// Labels of the reference cloud's `label` field.
constexpr int32_t kLabelGround = 0;
constexpr int32_t kLabelObject = 1;

/// The surfaces of `world` inside the fenced site, without sensor noise: every ground grid
/// vertex (the gravel surface rays hit) not covered by a structure, and points drawn
/// uniformly on every primitive surface at about one per `object_spacing_m`^2, keeping those
/// above the ground and not buried in another primitive. Intensity = 255 * reflectivity.
io::CloudFile ReferenceCloud(const Site& site, const World& world, double object_spacing_m,
                             uint64_t seed);

/// Writes the true terrain slope (deg) over the fenced site on a `resolution_m` grid, as
/// text: '#' comments, then `origin_m X Y`, `resolution_m R`, `size COLS ROWS`, then ROWS
/// lines of COLS values; row 0 is the southmost (y = origin), values go east. The slope is
/// atan(|grad h|) of the ground without gravel roughness (trenches included), by central
/// differences over +-resolution/2 at each cell centre. Throws naming the file on failure.
void WriteSlopeGrid(const std::string& path, const Site& site, double resolution_m);

}  // namespace hylo::sim
