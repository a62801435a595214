#pragma once
// Filling unknown cells of a raster (Pingel et al. 2013, Sec. 2.1 and 2.3: empty cells of the
// minimum surface, then the cells flagged as objects, are "inpainted" from their surroundings).
// The paper uses D'Errico's inpaint_nans; here the same idea, a membrane: every unknown cell
// takes the mean of its four neighbours (a discrete Laplace equation with the known cells
// fixed), so a gap is spanned by the smoothest surface that meets its rim, and a building's
// footprint by the terrain around it. At the grid border the missing neighbours are left out.
// The membrane serves the morphology (a smooth fill of empty cells); the DEM that points are
// classified against is filled with tangent planes instead (below), which keep the slopes.

#include <cstddef>

#include "hylo/terrain/ground_smrf_raster.h"

namespace hylo::terrain::smrf {

/// Replaces every NaN cell of `raster` by the membrane's height. Solved coarse to fine: the
/// grid is halved until it is small, the coarse solution is interpolated up as the start of a
/// few relaxation sweeps at each finer level, so large gaps cost no more per cell than small
/// ones. Returns the number of cells filled. Throws hylo::InternalError when no cell is known.
std::size_t InpaintMembrane(Raster* raster);

/// Replaces every NaN cell by the blend of the known cells' tangent planes: each known cell
/// carries its height and its gradient (read off the membrane through the known cells), and
/// an unknown cell takes the mean of those planes extended to it, weighted as the membrane
/// weighs the heights. Planes are reproduced as the membrane reproduces them; unlike the
/// membrane, which can never rise above the rim of a gap (maximum principle), this continues
/// the slopes around a gap into it, so a ridge, an embankment or a hilltop whose cells were
/// taken out comes back as one. Returns the number of cells filled; throws
/// hylo::InternalError when no cell is known.
std::size_t InpaintTangentPlanes(Raster* raster);

}  // namespace hylo::terrain::smrf
