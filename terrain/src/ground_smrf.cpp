#include "hylo/terrain/ground_smrf.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "hylo/common/check.h"
#include "hylo/common/local_origin.h"
#include "hylo/common/option_checks.h"
#include "hylo/terrain/ground_smrf_dem.h"
#include "hylo/terrain/ground_smrf_inpaint.h"
#include "hylo/terrain/ground_smrf_morphology.h"

namespace hylo::terrain {
namespace {

// The paper converts window radii from metres to cells by rounding up; the tolerance keeps
// 18 m / 1 m at 18 cells despite rounding in the division.
int CellsFor(double length_m, double cell_m) {
  return static_cast<int>(std::ceil(length_m / cell_m - 1e-9));
}

// Horizontal bounding box of the finite points; false when there is none.
bool FiniteBounds(const PointCloud& points, Eigen::Vector2d* min_xy, Eigen::Vector2d* max_xy) {
  bool any = false;
  for (const Eigen::Vector3f& p : points) {
    if (!p.allFinite()) continue;
    const Eigen::Vector2d xy = p.head<2>().cast<double>();
    *min_xy = any ? min_xy->cwiseMin(xy) : xy;
    *max_xy = any ? max_xy->cwiseMax(xy) : xy;
    any = true;
  }
  return any;
}

// Step 2: low outliers are the peaks of the inverted minimum surface.
std::vector<uint8_t> FindLowOutlierCells(const smrf::Raster& minimum_filled,
                                         const SmrfOptions& options) {
  if (options.low_outlier_window_m <= 0.0) return std::vector<uint8_t>(minimum_filled.Size(), 0);
  smrf::Raster inverted = minimum_filled;
  for (float& z : inverted.z) z = -z;
  return smrf::ProgressiveFilter(inverted, options.low_outlier_slope,
                                 CellsFor(options.low_outlier_window_m, options.cell_m));
}

bool AnyKnown(const smrf::Raster& raster) {
  return std::any_of(raster.z.begin(), raster.z.end(), [](float z) { return !std::isnan(z); });
}

SmrfResult NotClassified(std::size_t num_points, std::string message) {
  SmrfResult result;
  result.labels.assign(num_points, GroundLabel::kInvalid);
  result.height_above_surface_m.assign(num_points, std::numeric_limits<float>::quiet_NaN());
  result.num_invalid = num_points;
  result.message = std::move(message);
  return result;
}

}  // namespace

bool SmrfOptions::IsValid(std::string* why) const {
  if (!CheckPositive("cell_m", cell_m, why) || !CheckPositive("slope", slope, why)) return false;
  if (!(std::isfinite(max_window_m) && max_window_m >= cell_m)) {
    return FailOption("max_window_m", max_window_m, "must be finite and >= cell_m", why);
  }
  return CheckNonNegative("elevation_threshold_m", elevation_threshold_m, why) &&
         CheckNonNegative("elevation_scaler", elevation_scaler, why) &&
         CheckPositive("low_outlier_slope", low_outlier_slope, why) &&
         CheckNonNegative("low_outlier_window_m", low_outlier_window_m, why) &&
         (max_cells >= 1.0 || FailOption("max_cells", max_cells, "must be >= 1", why));
}

SmrfSurface ComputeSmrfSurface(const PointCloud& points_local, const SmrfOptions& options,
                               const SmrfProgress& progress) {
  Eigen::Vector2d min_xy, max_xy;
  HYLO_CHECK(FiniteBounds(points_local, &min_xy, &max_xy), "at least one finite point");
  SmrfSurface surface;
  // Step 1: the minimum surface, its empty cells inpainted for the morphology.
  smrf::Raster minimum = smrf::CoveringRaster(min_xy, max_xy, options.cell_m);
  std::vector<Eigen::Vector2f> lowest_offset_m;
  surface.num_cells_with_points =
      smrf::FillMinimumSurface(points_local, &minimum, &lowest_offset_m);
  smrf::Raster filled = minimum;
  smrf::InpaintMembrane(&filled);
  // Step 2. The paper only keeps low outliers out of the DEM; here they are also taken out of
  // the surface the opening sees, and their cells refilled from around them: left in, every
  // window that covers one is opened down to its depth, and where such pits are common (one
  // per few hundred m^2) nearly every cell ends up flagged.
  const std::vector<uint8_t> low = FindLowOutlierCells(filled, options);
  if (std::find(low.begin(), low.end(), 1) != low.end()) {
    smrf::Raster without_low = minimum;
    for (std::size_t i = 0; i < low.size(); ++i) {
      if (low[i]) without_low.z[i] = std::numeric_limits<float>::quiet_NaN();
    }
    if (AnyKnown(without_low)) {
      smrf::InpaintMembrane(&without_low);
      filled = std::move(without_low);
    }
  }
  // Step 3.
  surface.max_window_cells = CellsFor(options.max_window_m, options.cell_m);
  const std::vector<uint8_t> object =
      smrf::ProgressiveFilter(filled, options.slope, surface.max_window_cells, progress);
  for (std::size_t i = 0; i < object.size(); ++i) {
    surface.num_low_outlier_cells += low[i];
    surface.num_object_cells += object[i] && !low[i];
  }
  // Step 4: the provisional DEM from the cells that hold ground points (ground_smrf_dem.h).
  // Cells that were empty stay unknown here too, so they are filled from ground cells only,
  // never from a roof.
  smrf::DemInput dem_input;
  dem_input.minimum = &minimum;
  dem_input.lowest_offset_m = &lowest_offset_m;
  dem_input.low_outlier = &low;
  dem_input.object = &object;
  dem_input.readmit_within_m = options.elevation_threshold_m;
  smrf::Dem dem = smrf::BuildDem(dem_input);
  surface.dem = std::move(dem.z);
  surface.num_readmitted_cells = dem.num_readmitted_cells;
  surface.dem_rounds = dem.rounds;
  surface.slope = smrf::SlopeOf(surface.dem);
  return surface;
}

void ClassifySmrf(const PointCloud& points_local, const SmrfSurface& surface,
                  double elevation_threshold_m, double elevation_scaler, SmrfResult* result) {
  result->labels.assign(points_local.size(), GroundLabel::kInvalid);
  result->height_above_surface_m.assign(points_local.size(),
                                        std::numeric_limits<float>::quiet_NaN());
  result->num_ground = result->num_objects = result->num_invalid = 0;
  // Height and slope side by side: one cache line per corner when points come in no order.
  const smrf::PairRaster dem_and_slope(surface.dem, surface.slope);
  for (std::size_t i = 0; i < points_local.size(); ++i) {
    const Eigen::Vector3f& p = points_local[i];
    if (!p.allFinite()) {
      ++result->num_invalid;
      continue;
    }
    const Eigen::Vector2d dem_slope = dem_and_slope.Sample(p.x(), p.y());
    const double above_m = p.z() - dem_slope.x();
    const double threshold_m = elevation_threshold_m + elevation_scaler * dem_slope.y();
    result->height_above_surface_m[i] = static_cast<float>(above_m);
    const bool ground = std::abs(above_m) <= threshold_m;
    result->labels[i] = ground ? GroundLabel::kGround : GroundLabel::kObject;
    ++(ground ? result->num_ground : result->num_objects);
  }
}

SmrfResult FilterGroundSmrfLocal(const PointCloud& points_local, const SmrfOptions& options,
                                 const SmrfProgress& progress) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  Eigen::Vector2d min_xy, max_xy;
  if (!FiniteBounds(points_local, &min_xy, &max_xy)) {
    return NotClassified(points_local.size(),
                         points_local.empty() ? "empty cloud" : "no finite point in the cloud");
  }
  const double cells = smrf::CoveringCellCount(min_xy, max_xy, options.cell_m);
  if (cells > options.max_cells) {
    std::ostringstream os;
    os << "the points span " << (max_xy - min_xy).x() << " m x " << (max_xy - min_xy).y()
       << " m: " << cells << " cells of " << options.cell_m << " m, more than max_cells "
       << options.max_cells << " (a point far from the rest, or a cell too small?)";
    return NotClassified(points_local.size(), os.str());
  }
  const SmrfSurface surface = ComputeSmrfSurface(points_local, options, progress);
  SmrfResult result;
  ClassifySmrf(points_local, surface, options.elevation_threshold_m, options.elevation_scaler,
               &result);
  result.ok = true;
  result.grid_cols = surface.dem.cols;
  result.grid_rows = surface.dem.rows;
  result.num_empty_cells = surface.dem.Size() - surface.num_cells_with_points;
  result.num_low_outlier_cells = surface.num_low_outlier_cells;
  result.num_object_cells = surface.num_object_cells;
  result.num_readmitted_cells = surface.num_readmitted_cells;
  std::ostringstream os;
  os << result.num_ground << " ground, " << result.num_objects << " objects, grid "
     << result.grid_cols << "x" << result.grid_rows << " of " << options.cell_m << " m, "
     << surface.max_window_cells << " openings, " << result.num_object_cells << " object ("
     << result.num_readmitted_cells << " re-admitted) and " << result.num_low_outlier_cells
     << " low-outlier cells, " << surface.dem_rounds << " DEM rounds";
  result.message = os.str();
  return result;
}

SmrfResult FilterGroundSmrf(const std::vector<Eigen::Vector3d>& points_world,
                            const SmrfOptions& options, const SmrfProgress& progress) {
  const Eigen::Vector3d origin_world = ChooseOrigin(points_world);
  SmrfResult result = FilterGroundSmrfLocal(ToLocal(points_world, origin_world), options, progress);
  result.origin_world = origin_world;
  return result;
}

}  // namespace hylo::terrain
