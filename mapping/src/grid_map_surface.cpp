#include "hylo/mapping/grid_map_surface.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "hylo/common/check.h"

namespace hylo::mapping {
namespace {

constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();
constexpr double kRadToDeg = 180.0 / M_PI;

/// First and second moments of a set of points, so a neighbourhood's covariance is the sum
/// of its cells' moments (each cell's points are read once, not once per neighbour).
/// `n` is the sum of the weights, `count` the number of points behind it.
struct Moments {
  double n = 0.0;
  double count = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_outer = Eigen::Matrix3d::Zero();

  void Add(const Moments& o, double weight) {
    n += weight * o.n;
    count += o.count;
    sum += weight * o.sum;
    sum_outer += weight * o.sum_outer;
  }
};

/// Per-cell moments with x, y relative to the cell centre, so the sums stay small and the
/// covariance E[pp^T] - mean mean^T does not cancel large numbers.
std::vector<Moments> CellMoments(const registration::PointCloud& ground_local,
                                 const CellPoints& bins, const GridGeometry& g) {
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

/// Moments of `m` re-expressed after moving their xy frame by `shift` (p -> p + shift).
Moments Shifted(const Moments& m, const Eigen::Vector2d& shift) {
  Moments out = m;
  const Eigen::Vector3d s(shift.x(), shift.y(), 0.0);
  out.sum = m.sum + m.n * s;
  out.sum_outer =
      m.sum_outer + m.sum * s.transpose() + s * m.sum.transpose() + m.n * s * s.transpose();
  return out;
}

/// Cell offsets (dc, dr) whose centres are within `radius_cells`, always including the four
/// direct neighbours when `at_least_neighbours`.
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

/// A neighbourhood for the plane fit: cell offsets with their weights. Biweight kernel
/// (1 - (d/h)^2)^2 on the centre distance d with h one cell beyond the radius, so the outermost
/// cells still count a little: a smooth kernel keeps the normal of a curved or broken surface
/// centred on the cell instead of the footprint's mean (weighted PCA, e.g. Pauly et al. 2002).
struct Kernel {
  std::vector<Eigen::Vector2i> offsets;
  std::vector<double> weights;
};

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
    if (m.n > 0) around.Add(Shifted(m, d.cast<double>() * g.resolution_m), kernel.weights[k]);
  }
  return around;
}

struct PlaneFit {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // z up
  double rms_distance_m = 0.0;
};

enum class FitStatus { kOk, kTooFewPoints, kDegenerate };

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
  return FitStatus::kOk;
}

void ComputeStep(const GridGeometry& g, double step_radius_m, GridMap* grid) {
  const std::vector<float>& elevation = grid->Layer(layers::kElevation);
  std::vector<float>& step = grid->AddLayer(layers::kStep, kNoData);
  const std::vector<Eigen::Vector2i> window = Window(step_radius_m / g.resolution_m, true);
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    if (std::isnan(elevation[cell])) continue;
    float max_difference = 0.f;
    for (const Eigen::Vector2i& d : window) {
      const int col = g.Col(cell) + d.x(), row = g.Row(cell) + d.y();
      if (!g.Contains(col, row)) continue;
      const float other = elevation[g.Index(col, row)];
      if (std::isnan(other)) continue;
      max_difference = std::max(max_difference, std::abs(other - elevation[cell]));
    }
    step[cell] = max_difference;
  }
}

}  // namespace

bool SurfaceOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(normal_radius_m > 0.0) || !std::isfinite(normal_radius_m)) {
    os << "normal_radius_m = " << normal_radius_m << " must be finite and > 0";
  } else if (!(fallback_radius_m >= normal_radius_m) || !std::isfinite(fallback_radius_m)) {
    os << "fallback_radius_m = " << fallback_radius_m
       << " must be finite and >= normal_radius_m = " << normal_radius_m;
  } else if (min_points < 3) {
    os << "min_points = " << min_points << " must be >= 3 (a plane needs 3 points)";
  } else if (!(min_spread_cells >= 0.0)) {
    os << "min_spread_cells = " << min_spread_cells << " must be >= 0";
  } else if (!(step_radius_m > 0.0) || !std::isfinite(step_radius_m)) {
    os << "step_radius_m = " << step_radius_m << " must be finite and > 0";
  }
  if (why) *why = os.str();
  return os.str().empty();
}

SurfaceSummary ComputeSurfaceLayers(const registration::PointCloud& ground_local,
                                    const CellPoints& bins, const SurfaceOptions& options,
                                    GridMap* grid) {
  const GridGeometry& g = grid->geometry();
  HYLO_CHECK(bins.offsets.size() == g.NumCells() + 1, "bins come from another grid");
  const std::vector<float>& elevation = grid->Layer(layers::kElevation);
  std::vector<float>* out[6];
  const char* names[6] = {layers::kNormalX, layers::kNormalY,   layers::kNormalZ,
                          layers::kSlope,   layers::kRoughness, layers::kStep};
  for (int i = 0; i < 5; ++i) out[i] = &grid->AddLayer(names[i], kNoData);
  const std::vector<Moments> moments = CellMoments(ground_local, bins, g);
  const Kernel footprint = MakeKernel(options.normal_radius_m, g.resolution_m);
  const Kernel fallback = MakeKernel(options.fallback_radius_m, g.resolution_m);
  SurfaceSummary summary;
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    if (std::isnan(elevation[cell])) continue;
    PlaneFit fit;
    FitStatus status = FitPlane(Gather(moments, g, cell, footprint), options, g.resolution_m, &fit);
    // A sparse footprint (far from the sensor, one scan line) borrows from a wider ring: a
    // smoother slope is more useful to a planner than an unknown cell.
    if (status != FitStatus::kOk && options.fallback_radius_m > options.normal_radius_m) {
      status = FitPlane(Gather(moments, g, cell, fallback), options, g.resolution_m, &fit);
      summary.cells_fallback += status == FitStatus::kOk;
    }
    if (status == FitStatus::kTooFewPoints) ++summary.cells_too_few_points;
    if (status == FitStatus::kDegenerate) ++summary.cells_degenerate;
    if (status != FitStatus::kOk) continue;
    ++summary.cells_with_normal;
    for (int i = 0; i < 3; ++i) (*out[i])[cell] = static_cast<float>(fit.normal(i));
    (*out[3])[cell] = static_cast<float>(std::acos(std::min(fit.normal.z(), 1.0)) * kRadToDeg);
    (*out[4])[cell] = static_cast<float>(fit.rms_distance_m);
  }
  ComputeStep(g, options.step_radius_m, grid);
  return summary;
}

}  // namespace hylo::mapping
