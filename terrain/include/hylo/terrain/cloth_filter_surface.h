#pragma once
// The surface the cloth lands on (Zhang et al. 2016, Sec. 2.2, "intersection check"): for each
// particle, the height of the inverted point nearest to it horizontally among the points of its
// cell. Particles with no point (gaps, water, the grid border) get a height filled in from
// measured particles, so that every particle has something to stop on.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/terrain/cloth_filter.h"
#include "hylo/terrain/cloth_filter_cloth.h"

namespace hylo::terrain::cloth {

struct InvertedSurface {
  std::vector<double> height_m;      ///< one per particle (ClothGrid::Index), m
  std::size_t num_filled_holes = 0;  ///< particles whose height was filled in
};

/// `points_inverted` must be finite and inside the grid (the grid covers their bounding box).
/// Throws hylo::InternalError when no point falls in the grid (the caller checks for empty
/// clouds first).
InvertedSurface RasterizeInvertedSurface(const ClothGrid& grid, const PointCloud& points_inverted,
                                         ClothHoleFill hole_fill = ClothHoleFill::kNeighbourMean);

/// Fills NaN entries of `height_m` breadth-first from the known ones: each ring of unknown
/// particles takes the mean of its already-known 4-neighbours. Returns how many were filled.
std::size_t FillHoles(const ClothGrid& grid, std::vector<double>* height_m);

/// Gives every NaN entry of `height_m` the value of the known entry nearest to it (Euclidean
/// distance on the grid, found by propagating nearest sources outwards; ties go to the first
/// found). Returns how many were filled.
std::size_t FillHolesFromNearest(const ClothGrid& grid, std::vector<double>* height_m);

/// Fills NaN entries of `height_m` as the reference implementation does: the first measured
/// particle along the row (towards +x, then -x), else along the column (towards -y, then +y);
/// holes with neither take a nearest filled value. Returns how many were filled.
std::size_t FillHolesAsReference(const ClothGrid& grid, std::vector<double>* height_m);

/// Flags (1) the points of `points_inverted` that stand more than `depth_m` above (inverted:
/// below, in the original cloud) nearly all other points in the 3x3 block of `cell_m` cells
/// around them: fewer than `min_support` of those points, or fewer than `max_fraction` of them,
/// reach within `depth_m` of the point. These are low outliers (single or in clusters), which
/// the cloth would hang on.
std::vector<uint8_t> FindLowOutliers(const PointCloud& points_inverted, double cell_m,
                                     double depth_m, int min_support, double max_fraction);

}  // namespace hylo::terrain::cloth
