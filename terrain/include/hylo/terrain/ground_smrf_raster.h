#pragma once
// The elevation raster SMRF works on (Pingel et al. 2013, Sec. 2.1): a regular grid of square
// cells over the points' bounding box, one height per cell, NaN where a cell is unknown. Cell
// (col, row) covers [origin + col * cell, origin + (col + 1) * cell) along x (row along y); its
// value stands at the cell centre, which is where interpolation puts it.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <vector>

#include "hylo/common/point_types.h"

namespace hylo::terrain::smrf {

struct Raster {
  Eigen::Vector2d origin_xy = Eigen::Vector2d::Zero();  ///< lower-left corner of cell (0, 0), m
  double cell_m = 1.0;                                  ///< cell side, m
  int cols = 0;                                         ///< cells along x
  int rows = 0;                                         ///< cells along y
  std::vector<float> z;  ///< one value per cell, row-major (Index), NaN = unknown

  std::size_t Size() const { return static_cast<std::size_t>(cols) * rows; }
  std::size_t Index(int col, int row) const { return static_cast<std::size_t>(row) * cols + col; }
  bool Contains(int col, int row) const { return col >= 0 && row >= 0 && col < cols && row < rows; }
  /// The cell holding (x, y), clamped to the grid (points on the far edge of the bounding box
  /// fall just past the last cell).
  void CellOf(float x, float y, int* col, int* row) const;
  /// Bilinear interpolation between cell centres (clamped at the border); every cell must be
  /// known (filled).
  double Sample(double x, double y) const;
};

/// Two rasters of one geometry interleaved, sampled together (bilinear, as Raster::Sample).
class PairRaster {
 public:
  PairRaster(const Raster& first, const Raster& second);
  /// (first, second) at (x, y).
  Eigen::Vector2d Sample(double x, double y) const;

 private:
  Raster geometry_;                      ///< z left empty
  std::vector<Eigen::Vector2f> values_;  ///< per cell, row-major
};

/// An empty raster (z all NaN) of `cell_m` cells covering [min_xy, max_xy].
Raster CoveringRaster(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, double cell_m);

/// Number of cells CoveringRaster would allocate (computed in double, so that a stray point
/// kilometres away gives a huge number instead of an overflow).
double CoveringCellCount(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy,
                         double cell_m);

/// The paper's ZImin: each cell takes the lowest z of the finite points in it; cells without a
/// point stay NaN. Returns how many cells got a point. When `lowest_offset_m` is given, it
/// gets one entry per cell: where the lowest point lies relative to the cell centre (x, y, m;
/// zero for cells without a point).
std::size_t FillMinimumSurface(const PointCloud& points, Raster* raster,
                               std::vector<Eigen::Vector2f>* lowest_offset_m = nullptr);

/// The gradient of `dem` at cell (col, row) in rise per cell along x and y: central
/// differences, one-sided at the border, zero along an axis of one cell. The cell and its four
/// neighbours must be known.
Eigen::Vector2d GradientPerCell(const Raster& dem, int col, int row);

/// Magnitude of the gradient (rise over run) by central differences, one-sided at the border;
/// `dem` must be fully known. The result has dem's geometry.
Raster SlopeOf(const Raster& dem);

}  // namespace hylo::terrain::smrf
