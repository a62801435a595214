#pragma once
// The surface the cloth lands on (Zhang et al. 2016, Sec. 2.2, "intersection check"): for each
// particle, the height of the inverted point nearest to it horizontally among the points of its
// cell. Particles with no point (gaps, water, the grid border) get a height filled in from
// their neighbours, so that every particle has something to stop on.

#include <cstddef>
#include <vector>

#include "hylo/mapping/cloth_filter_cloth.h"
#include "hylo/registration/point_types.h"

namespace hylo::mapping::cloth {

struct InvertedSurface {
  std::vector<double> height_m;      ///< one per particle (ClothGrid::Index), m
  std::size_t num_filled_holes = 0;  ///< particles whose height was filled in
};

/// `points_inverted` must be finite and inside the grid (the grid covers their bounding box).
/// Throws hylo::InternalError when no point falls in the grid (the caller checks for empty
/// clouds first).
InvertedSurface RasterizeInvertedSurface(const ClothGrid& grid,
                                         const registration::PointCloud& points_inverted);

/// Fills NaN entries of `height_m` breadth-first from the known ones: each ring of unknown
/// particles takes the mean of its already-known 4-neighbours. Returns how many were filled.
std::size_t FillHoles(const ClothGrid& grid, std::vector<double>* height_m);

}  // namespace hylo::mapping::cloth
