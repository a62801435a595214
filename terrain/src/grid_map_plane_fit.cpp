#include "grid_map_plane_fit.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace hylo::terrain::internal {
namespace {

/// Moments of `m` re-expressed after moving their xy frame by `shift` (p -> p + shift).
Moments Shifted(const Moments& m, const Eigen::Vector2d& shift) {
  Moments out = m;
  const Eigen::Vector3d s(shift.x(), shift.y(), 0.0);
  out.sum = m.sum + m.n * s;
  out.sum_outer =
      m.sum_outer + m.sum * s.transpose() + s * m.sum.transpose() + m.n * s * s.transpose();
  return out;
}

}  // namespace

void Moments::AddCell(const Moments& cell, double weight) {
  n += weight * cell.n;
  count += cell.count;
  cell_weight += weight;
  cell_weight_sq += weight * weight;
  sum += weight * cell.sum;
  sum_outer += weight * cell.sum_outer;
}

std::vector<Moments> CellMoments(const PointCloud& ground_local, const CellPoints& bins,
                                 const GridGeometry& g) {
  std::vector<Moments> moments(g.NumCells());
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    const Eigen::Vector2d centre = g.CentreLocal(g.Col(cell), g.Row(cell));
    Moments& m = moments[cell];
    for (std::size_t k = bins.offsets[cell]; k < bins.offsets[cell + 1]; ++k) {
      Eigen::Vector3d p = ground_local[bins.point_indices[k]].cast<double>();
      p.head<2>() -= centre;
      m.n += 1.0;
      m.count += 1.0;
      m.sum += p;
      m.sum_outer += p * p.transpose();
    }
  }
  return moments;
}

std::vector<Eigen::Vector2i> Window(double radius_cells, bool at_least_neighbours) {
  std::vector<Eigen::Vector2i> offsets;
  const double r = at_least_neighbours ? std::max(radius_cells, 1.0) : radius_cells;
  const int k = static_cast<int>(std::floor(r));
  for (int dr = -k; dr <= k; ++dr) {
    for (int dc = -k; dc <= k; ++dc) {
      if (dc * dc + dr * dr <= r * r + 1e-9) offsets.emplace_back(dc, dr);
    }
  }
  return offsets;
}

Kernel MakeKernel(double radius_m, double resolution_m) {
  Kernel kernel;
  kernel.offsets = Window(radius_m / resolution_m, true);
  const double h = radius_m / resolution_m + 1.0;  // cells
  for (const Eigen::Vector2i& d : kernel.offsets) {
    const double q = d.cast<double>().squaredNorm() / (h * h);
    kernel.weights.push_back((1.0 - q) * (1.0 - q));
  }
  return kernel;
}

Moments Gather(const std::vector<Moments>& moments, const GridGeometry& g, std::size_t cell,
               const Kernel& kernel) {
  Moments around;
  for (std::size_t k = 0; k < kernel.offsets.size(); ++k) {
    const Eigen::Vector2i& d = kernel.offsets[k];
    const int col = g.Col(cell) + d.x(), row = g.Row(cell) + d.y();
    if (!g.Contains(col, row)) continue;
    const Moments& m = moments[g.Index(col, row)];
    if (m.n > 0) around.AddCell(Shifted(m, d.cast<double>() * g.resolution_m), kernel.weights[k]);
  }
  return around;
}

double PlaneFit::TiltStdRad(double sigma_m) const {
  const double information = effective_cells * min_spread_var_m2;
  return information > 0.0 ? sigma_m / std::sqrt(information) : M_PI;
}

FitStatus FitPlane(const Moments& m, const SurfaceOptions& options, double resolution_m,
                   PlaneFit* fit) {
  if (m.count < options.min_points) return FitStatus::kTooFewPoints;
  const Eigen::Vector3d mean = m.sum / m.n;
  const Eigen::Matrix3d covariance = m.sum_outer / m.n - mean * mean.transpose();
  // The horizontal spread must cover both axes, or the tilt across a line is unobserved.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> xy(covariance.topLeftCorner<2, 2>());
  const double min_spread = options.min_spread_cells * resolution_m;
  if (xy.eigenvalues()(0) < min_spread * min_spread) return FitStatus::kDegenerate;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(covariance);
  fit->normal = pca.eigenvectors().col(0);  // smallest eigenvalue: the plane normal
  if (fit->normal.z() < 0.0) fit->normal = -fit->normal;
  fit->rms_distance_m = std::sqrt(std::max(pca.eigenvalues()(0), 0.0));
  fit->min_spread_var_m2 = std::max(pca.eigenvalues()(1), 0.0);
  fit->effective_cells = m.EffectiveCells();
  return FitStatus::kOk;
}

}  // namespace hylo::terrain::internal
