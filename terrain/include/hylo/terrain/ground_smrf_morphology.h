#pragma once
// Grey-scale morphology on a raster and SMRF's progressive opening (Pingel et al. 2013,
// Sec. 2.2).
//
// The paper opens with a disk. Here the disk of radius k cells is an octagon, the Minkowski
// sum of a horizontal, a vertical and two diagonal lines (MATLAB's strel('disk'), which the
// paper used, is such a sum of lines too). Erosion by a sum of lines is a sequence of erosions
// by each line, and a line erosion costs three comparisons per cell whatever its length (van
// Herk 1992; Gil & Werman 1993), so an opening costs the same at 1 m and at 20 m: what keeps
// SMRF within a second per million points.

#include <cstdint>
#include <functional>
#include <vector>

#include "hylo/terrain/ground_smrf_raster.h"

namespace hylo::terrain::smrf {

/// H(axis) + V(axis) + D1(diagonal) + D2(diagonal): lines of 2 * axis + 1 cells along x and y
/// and of 2 * diagonal + 1 cells along both diagonals. It reaches axis + 2 * diagonal cells
/// along x and y and axis + diagonal cells (times sqrt 2) along the diagonals.
struct Octagon {
  int axis = 0;
  int diagonal = 0;
};

/// The octagon closest to a disk of `radius_cells` (>= 1): it reaches exactly radius_cells
/// along x and y and within 0.71 cells of it along the diagonals (0.83 at radius 2, a 5 x 5
/// square); axis >= 1, so that its cells form a solid block (two diagonal lines alone cover
/// every other cell only).
Octagon OctagonForRadius(int radius_cells);

/// In place, on a fully known (NaN-free) cols x rows row-major grid; cells outside the grid
/// are left out of each minimum / maximum.
void Erode(int cols, int rows, const Octagon& element, std::vector<float>* z);
void Dilate(int cols, int rows, const Octagon& element, std::vector<float>* z);
/// Erosion then dilation: removes raised features the element does not fit in.
void Open(int cols, int rows, const Octagon& element, std::vector<float>* z);

/// The paper's progressive filter on a fully known surface: the surface is opened with
/// windows of radius 1, 2, ... max_radius_cells (linearly growing), each opening applied to
/// the previous one; a cell is flagged (1) once the drop between two successive surfaces
/// exceeds slope * radius * cell_m. `progress(k, max_radius_cells)` is called after each
/// opening when set.
std::vector<uint8_t> ProgressiveFilter(const Raster& surface, double slope, int max_radius_cells,
                                       const std::function<void(int, int)>& progress = {});

}  // namespace hylo::terrain::smrf
