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
struct Moments {
  double n = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_outer = Eigen::Matrix3d::Zero();

  void Add(const Moments& o) {
    n += o.n;
    sum += o.sum;
    sum_outer += o.sum_outer;
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
  const double r = at_least_neighbours ? std::max(radius_cells, 1.0) : radius_cells;
  const int k = static_cast<int>(std::floor(r));
  std::vector<Eigen::Vector2i> offsets;
  for (int dr = -k; dr <= k; ++dr) {
    for (int dc = -k; dc <= k; ++dc) {
      if (dc * dc + dr * dr <= r * r + 1e-9) offsets.emplace_back(dc, dr);
    }
  }
  return offsets;
}

struct PlaneFit {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // z up
  double rms_distance_m = 0.0;
};

enum class FitStatus { kOk, kTooFewPoints, kDegenerate };

FitStatus FitPlane(const Moments& m, const SurfaceOptions& options, double resolution_m,
                   PlaneFit* fit) {
  if (m.n < options.min_points) return FitStatus::kTooFewPoints;
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
  const std::vector<Eigen::Vector2i> window =
      Window(options.normal_radius_m / g.resolution_m, false);
  SurfaceSummary summary;
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    if (std::isnan(elevation[cell])) continue;
    Moments around;
    for (const Eigen::Vector2i& d : window) {
      const int col = g.Col(cell) + d.x(), row = g.Row(cell) + d.y();
      if (!g.Contains(col, row)) continue;
      const Moments& m = moments[g.Index(col, row)];
      if (m.n > 0) around.Add(Shifted(m, d.cast<double>() * g.resolution_m));
    }
    PlaneFit fit;
    const FitStatus status = FitPlane(around, options, g.resolution_m, &fit);
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
