#include "hylo/terrain/grid_map_surface.h"

#include <Eigen/Geometry>  // cross
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "grid_map_plane_fit.h"
#include "hylo/common/check.h"

namespace hylo::terrain {
namespace {

constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();
constexpr double kRadToDeg = 180.0 / M_PI;

using internal::FitPlane;
using internal::FitStatus;
using internal::Kernel;
using internal::Moments;
using internal::PlaneFit;

/// The square blocks of 1, 2 x 2 and 3 x 3 cells that contain a cell, uniformly weighted:
/// next to a break (a trench wall, a bank's edge) some of them lie on the cell's side only,
/// and a wall or a floor one or two cells wide fits in one (non-centred neighbourhoods, as in
/// normal estimation near sharp features).
std::vector<Kernel> ContainingBlocks() {
  std::vector<Kernel> blocks;
  for (int size = 1; size <= 3; ++size) {
    for (int r0 = 1 - size; r0 <= 0; ++r0) {
      for (int c0 = 1 - size; c0 <= 0; ++c0) {
        Kernel block;
        for (int dr = r0; dr < r0 + size; ++dr) {
          for (int dc = c0; dc < c0 + size; ++dc) block.offsets.emplace_back(dc, dr);
        }
        block.weights.assign(block.offsets.size(), 1.0);
        blocks.push_back(std::move(block));
      }
    }
  }
  return blocks;
}

/// Of the blocks containing `cell`, the most planar: the smallest unbiased residual variance
/// (the plane's 3 parameters taken off the point count, so small blocks are not favoured).
bool FitBestBlock(const std::vector<Moments>& moments, const GridGeometry& g, std::size_t cell,
                  const std::vector<Kernel>& blocks, const SurfaceOptions& options,
                  PlaneFit* best) {
  double best_variance = std::numeric_limits<double>::infinity();
  for (const Kernel& block : blocks) {
    const Moments around = internal::Gather(moments, g, cell, block);
    PlaneFit fit;
    if (FitPlane(around, options, g.resolution_m, &fit) != FitStatus::kOk) continue;
    const double variance =
        fit.rms_distance_m * fit.rms_distance_m * around.count / (around.count - 3.0);
    if (variance < best_variance) {
      best_variance = variance;
      *best = fit;
    }
  }
  return std::isfinite(best_variance);
}

/// True when one of the cell's four neighbours has no elevation (no ground point and not a
/// filled small hole) or lies outside the grid: the unseen side may hide a drop, e.g. the
/// occluded wall of a trench whose lip alone was hit, that the points around cannot show.
bool AtDataEdge(const GridGeometry& g, const std::vector<float>& elevation, std::size_t cell) {
  static const int kDc[4] = {1, -1, 0, 0}, kDr[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const int col = g.Col(cell) + kDc[k], row = g.Row(cell) + kDr[k];
    if (!g.Contains(col, row) || std::isnan(elevation[g.Index(col, row)])) return true;
  }
  return false;
}

/// Angle between two unit normals, rad.
double AngleRad(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// Intersection of confidence intervals (Katkovnik 1999; Goldenshluger & Nemirovski 1997):
/// walking from the finest scale up, a scale is kept while its normal agrees with every
/// finer one within `sigmas` times the sum of their tilt standard deviations; the last
/// scale kept is the largest over which the surface is still one plane, so a flat cell gets
/// the footprint's low-noise normal and a cell on a bank or trench wall its own. Returns the
/// index into `fits` of the chosen fit (fits with `ok` false are skipped).
std::size_t SelectScale(const std::vector<PlaneFit>& fits, const std::vector<char>& ok,
                        double sigma_m, double sigmas) {
  std::size_t chosen = fits.size();
  for (std::size_t k = 0; k < fits.size(); ++k) {
    if (!ok[k]) continue;
    const double std_k = fits[k].TiltStdRad(sigma_m);
    for (std::size_t j = 0; j < k; ++j) {
      if (!ok[j]) continue;
      const double bound = sigmas * (fits[j].TiltStdRad(sigma_m) + std_k);
      if (AngleRad(fits[j].normal, fits[k].normal) > bound) return chosen;
    }
    chosen = k;
  }
  return chosen;
}

/// Height noise of the map: the median RMS distance of the footprint fits to their planes.
/// Most cells are smooth at the footprint scale, so the median is the noise (gravel, range
/// noise), not the shape.
double MedianFootprintRms(const std::vector<Moments>& moments, const GridGeometry& g,
                          const std::vector<float>& elevation, const Kernel& footprint,
                          const SurfaceOptions& options) {
  std::vector<double> rms;
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    if (std::isnan(elevation[cell]) || moments[cell].count == 0) continue;
    PlaneFit fit;
    if (FitPlane(internal::Gather(moments, g, cell, footprint), options, g.resolution_m, &fit) ==
        FitStatus::kOk) {
      rms.push_back(fit.rms_distance_m);
    }
  }
  if (rms.empty()) return 0.0;
  std::nth_element(rms.begin(), rms.begin() + rms.size() / 2, rms.end());
  return rms[rms.size() / 2];
}

void ComputeStep(const GridGeometry& g, double step_radius_m, GridMap* grid) {
  const std::vector<float>& elevation = grid->Layer(layers::kElevation);
  std::vector<float>& step = grid->AddLayer(layers::kStep, kNoData);
  const std::vector<Eigen::Vector2i> window =
      internal::Window(step_radius_m / g.resolution_m, true);
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
  } else if (!(scale_consistency_sigmas >= 0.0) || !std::isfinite(scale_consistency_sigmas)) {
    os << "scale_consistency_sigmas = " << scale_consistency_sigmas << " must be finite and >= 0";
  } else if (!(step_radius_m > 0.0) || !std::isfinite(step_radius_m)) {
    os << "step_radius_m = " << step_radius_m << " must be finite and > 0";
  }
  if (why) *why = os.str();
  return os.str().empty();
}

SurfaceSummary ComputeSurfaceLayers(const PointCloud& ground_local, const CellPoints& bins,
                                    const SurfaceOptions& options, GridMap* grid) {
  const GridGeometry& g = grid->geometry();
  HYLO_CHECK(bins.offsets.size() == g.NumCells() + 1, "bins come from another grid");
  const std::vector<float>& elevation = grid->Layer(layers::kElevation);
  std::vector<float>* out[6];
  const char* names[6] = {layers::kNormalX, layers::kNormalY,   layers::kNormalZ,
                          layers::kSlope,   layers::kRoughness, layers::kStep};
  for (int i = 0; i < 5; ++i) out[i] = &grid->AddLayer(names[i], kNoData);
  const std::vector<Moments> moments = internal::CellMoments(ground_local, bins, g);
  const std::vector<Kernel> blocks = ContainingBlocks();
  const Kernel footprint = internal::MakeKernel(options.normal_radius_m, g.resolution_m);
  const Kernel fallback = internal::MakeKernel(options.fallback_radius_m, g.resolution_m);
  SurfaceSummary summary;
  summary.noise_m = MedianFootprintRms(moments, g, elevation, footprint, options);
  const bool adaptive = options.scale_consistency_sigmas > 0.0;
  std::vector<PlaneFit> fits(2);  // finest first: the most planar block, the footprint
  std::vector<char> ok(2, 0);
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    if (std::isnan(elevation[cell])) continue;
    if (options.unknown_at_data_edge && AtDataEdge(g, elevation, cell)) {
      ++summary.cells_at_data_edge;
      continue;
    }
    if (adaptive) ok[0] = FitBestBlock(moments, g, cell, blocks, options, &fits[0]);
    ok[1] = FitPlane(internal::Gather(moments, g, cell, footprint), options, g.resolution_m,
                     &fits[1]) == FitStatus::kOk;
    PlaneFit fit = fits.back();  // the footprint: roughness is a property at the vehicle scale
    FitStatus status = ok.back() ? FitStatus::kOk : FitStatus::kTooFewPoints;
    if (ok.back()) {
      const std::size_t k =
          SelectScale(fits, ok, summary.noise_m, options.scale_consistency_sigmas);
      fit.normal = fits[k].normal;
      summary.cells_finer_scale += k == 0;
    } else if (options.fallback_radius_m > options.normal_radius_m) {
      // A sparse footprint (far from the sensor, one scan line) borrows from a wider ring: a
      // smoother slope is more useful to a planner than an unknown cell.
      status =
          FitPlane(internal::Gather(moments, g, cell, fallback), options, g.resolution_m, &fit);
      summary.cells_fallback += status == FitStatus::kOk;
    } else {
      status =
          FitPlane(internal::Gather(moments, g, cell, footprint), options, g.resolution_m, &fit);
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

}  // namespace hylo::terrain
