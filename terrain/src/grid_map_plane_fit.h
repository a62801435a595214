#pragma once
// Plane fits over neighbourhoods of grid cells, shared by the surface layers
// (grid_map_surface.cpp). Internal to hylo::mapping: not installed.
//
// Each cell's points are summarised once by their moments; a neighbourhood's covariance is
// the kernel-weighted sum of its cells' moments, so a fit at any scale costs one pass over the
// neighbourhood's cells, not over its points.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/terrain/grid_map.h"
#include "hylo/terrain/grid_map_surface.h"

namespace hylo::terrain::internal {

/// First and second moments of a set of points. `n` is the sum of the point weights, `count`
/// the number of points behind it; `cell_weight` and `cell_weight_sq` sum the kernel weights
/// (and their squares) of the cells that gave points, for the effective number of cells.
struct Moments {
  double n = 0.0;
  double count = 0.0;
  double cell_weight = 0.0;
  double cell_weight_sq = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_outer = Eigen::Matrix3d::Zero();

  /// Adds one cell's moments with kernel weight `weight`.
  void AddCell(const Moments& cell, double weight);
  /// Independent samples behind the fit when the noise is shared within a cell (gravel,
  /// texture): the Kish effective size (sum w)^2 / sum w^2 of the cells' weights.
  double EffectiveCells() const {
    return cell_weight_sq > 0.0 ? cell_weight * cell_weight / cell_weight_sq : 0.0;
  }
};

/// Per-cell moments with x, y relative to the cell centre (small sums, no cancellation).
std::vector<Moments> CellMoments(const PointCloud& ground_local, const CellPoints& bins,
                                 const GridGeometry& g);

/// Cell offsets with their weights. Biweight kernel (1 - (d/h)^2)^2 on the centre distance d
/// with h one cell beyond the radius, so the outermost cells still count a little: a smooth
/// kernel keeps the normal of a curved surface centred on the cell (weighted PCA, Pauly et
/// al. 2002).
struct Kernel {
  std::vector<Eigen::Vector2i> offsets;
  std::vector<double> weights;
};
Kernel MakeKernel(double radius_m, double resolution_m);

/// Cell offsets (dc, dr) whose centres are within `radius_cells` (at least the four direct
/// neighbours when `at_least_neighbours`).
std::vector<Eigen::Vector2i> Window(double radius_cells, bool at_least_neighbours);

/// The moments of the kernel's cells around `cell`, in a frame centred on `cell`'s centre.
Moments Gather(const std::vector<Moments>& moments, const GridGeometry& g, std::size_t cell,
               const Kernel& kernel);

struct PlaneFit {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< z up
  double rms_distance_m = 0.0;                        ///< RMS distance of the points to the plane
  double min_spread_var_m2 = 0.0;  ///< in-plane variance along the less spread axis, m^2
  double effective_cells = 0.0;    ///< Moments::EffectiveCells of the fit

  /// Standard deviation of the normal's tilt, rad, for a per-cell height noise `sigma_m`:
  /// sigma / sqrt(cells * spread) (the slope of a least-squares line, per axis).
  double TiltStdRad(double sigma_m) const;
};

enum class FitStatus { kOk, kTooFewPoints, kDegenerate };

/// Weighted PCA plane: the eigenvector of the smallest covariance eigenvalue.
FitStatus FitPlane(const Moments& m, const SurfaceOptions& options, double resolution_m,
                   PlaneFit* fit);

}  // namespace hylo::terrain::internal
