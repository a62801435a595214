#pragma once
// SMRF's provisional DEM (Pingel et al. 2013, Sec. 2.3: the minimum surface without the cells
// flagged as objects, inpainted), with two additions that let it follow terrain the opening
// cannot tell from objects:
//   - each ground cell stands for its lowest point moved to the cell centre along the DEM's
//     slope: on a slope the lowest point of a cell lies on its downhill side, so the raw
//     minimum sits low by up to slope x half a cell, and every point of the cell looked that
//     much higher than it is;
//   - re-admission: a cell the opening flagged whose height lies within the elevation threshold
//     of the DEM built without it is ground after all (the test every point gets in step 5),
//     and the DEM is rebuilt with it until no cell changes. The opening flags the top of every
//     ridge, embankment or terrace edge narrower than its window; with the DEM's tangent-plane
//     fill (ground_smrf_inpaint.h) continuing the slopes around such a gap, its cells pass one
//     ring per round, while a roof stands a wall's height above the ground around it and never
//     does. This is the densification of progressive TIN filters (Axelsson 2000) on the
//     raster, seeded by the opening's ground cells.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hylo/terrain/ground_smrf_raster.h"

namespace hylo::terrain::smrf {

struct DemInput {
  const Raster* minimum = nullptr;  ///< lowest z per cell, NaN where a cell has no point
  const std::vector<Eigen::Vector2f>* lowest_offset_m = nullptr;  ///< per cell: its lowest
                                                                  ///< point - the cell centre
  const std::vector<uint8_t>* low_outlier = nullptr;              ///< per cell: never ground
  const std::vector<uint8_t>* object = nullptr;  ///< per cell: flagged by the opening
  double readmit_within_m = 0.5;  ///< re-admission tolerance (the elevation threshold), m
};

struct Dem {
  Raster z;                              ///< every cell known, m
  std::vector<uint8_t> ground;           ///< per cell: its height was kept (not inpainted)
  std::size_t num_readmitted_cells = 0;  ///< flagged by the opening, ground after all
  int rounds = 0;                        ///< DEMs built
};

/// The DEM of the cells that hold points and are neither low outliers nor objects, then
/// re-admission rounds until none admits a cell (at most kMaxDemRounds). When no cell
/// qualifies (a handful of points, all flagged), every cell with points does: the minimum
/// surface is then the best guess at the ground. `minimum` needs at least one known cell.
Dem BuildDem(const DemInput& input);

/// Upper bound on the rounds: each admits the next ring of cells around the ground; ISPRS
/// samples settle within 10, so this only bounds a pathological input.
constexpr int kMaxDemRounds = 30;

}  // namespace hylo::terrain::smrf
