#include "hylo/terrain/traversability_cost.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "hylo/common/check.h"

namespace hylo::terrain {
namespace {

constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();
constexpr const char* kObstaclePoints = "obstacle_points";

bool Positive(double v) { return v > 0.0 && std::isfinite(v); }

/// Ground height under a cell: its own elevation, else the mean of the nearest square ring of
/// cells with elevation within `max_ring` cells (an object hides the ground right under it).
float GroundHeight(const GridGeometry& g, const std::vector<float>& elevation, int col, int row,
                   int max_ring) {
  const float own = elevation[g.Index(col, row)];
  if (!std::isnan(own)) return own;
  for (int r = 1; r <= max_ring; ++r) {
    double sum = 0.0;
    int n = 0;
    for (int dr = -r; dr <= r; ++dr) {
      for (int dc = -r; dc <= r; ++dc) {
        if (std::max(std::abs(dc), std::abs(dr)) != r || !g.Contains(col + dc, row + dr)) continue;
        const float e = elevation[g.Index(col + dc, row + dr)];
        if (std::isnan(e)) continue;
        sum += e;
        ++n;
      }
    }
    if (n > 0) return static_cast<float>(sum / n);
  }
  return kNoData;
}

// Gradient of the elevation along one axis at a cell: the central difference when the cell
// and both neighbours have an elevation, else 0 (m per m). One-sided differences are left
// out: over a single cell the noise of two sparse cells' elevations alone can pass the limit.
double AxisGradient(const GridGeometry& g, const std::vector<float>& elevation, int col, int row,
                    int dc, int dr) {
  const auto at = [&](int c, int r) {
    return g.Contains(c, r) ? elevation[g.Index(c, r)] : kNoData;
  };
  const float here = at(col, row), ahead = at(col + dc, row + dr), behind = at(col - dc, row - dr);
  if (std::isnan(here) || std::isnan(ahead) || std::isnan(behind)) return 0.0;
  return (ahead - behind) / (2.0 * g.resolution_m);
}

// Slope of the elevation layer at the cell's own scale, deg. The plane fit over the vehicle
// footprint smooths a bank narrower than the footprint below the limit; the cell-scale
// gradient still sees it.
double CellGradeDeg(const GridGeometry& g, const std::vector<float>& elevation, std::size_t cell) {
  const int col = g.Col(cell), row = g.Row(cell);
  const double gx = AxisGradient(g, elevation, col, row, 1, 0);
  const double gy = AxisGradient(g, elevation, col, row, 0, 1);
  return std::atan(std::hypot(gx, gy)) * 180.0 / M_PI;
}

}  // namespace

const char* CellClassName(CellClass cell_class) {
  switch (cell_class) {
    case CellClass::kFree:
      return "free";
    case CellClass::kCost:
      return "cost";
    case CellClass::kLethal:
      return "lethal";
    case CellClass::kUnknown:
      break;
  }
  return "unknown";
}

bool CostOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  const double weight_sum = slope_weight + step_weight + roughness_weight;
  if (!Positive(max_slope_deg) || max_slope_deg >= 90.0) {
    os << "max_slope_deg = " << max_slope_deg << " must be in (0, 90)";
  } else if (!Positive(max_step_m)) {
    os << "max_step_m = " << max_step_m << " must be finite and > 0";
  } else if (!Positive(max_roughness_m)) {
    os << "max_roughness_m = " << max_roughness_m << " must be finite and > 0";
  } else if (!(slope_weight >= 0 && step_weight >= 0 && roughness_weight >= 0) ||
             !Positive(weight_sum)) {
    os << "slope_weight, step_weight, roughness_weight = " << slope_weight << ", " << step_weight
       << ", " << roughness_weight << " must be >= 0 with a finite sum > 0";
  } else if (!(free_cost_max >= 0.0 && free_cost_max <= 1.0)) {
    os << "free_cost_max = " << free_cost_max << " must be in [0, 1]";
  } else if (!(obstacle_min_height_m >= 0.0) || !std::isfinite(obstacle_min_height_m)) {
    os << "obstacle_min_height_m = " << obstacle_min_height_m << " must be finite and >= 0";
  } else if (!(obstacle_max_height_m > obstacle_min_height_m) ||
             !std::isfinite(obstacle_max_height_m)) {
    os << "obstacle_max_height_m = " << obstacle_max_height_m
       << " must be finite and > obstacle_min_height_m = " << obstacle_min_height_m;
  } else if (min_obstacle_points < 1) {
    os << "min_obstacle_points = " << min_obstacle_points << " must be >= 1";
  } else if (!(ground_search_radius_m >= 0.0) || !std::isfinite(ground_search_radius_m)) {
    os << "ground_search_radius_m = " << ground_search_radius_m << " must be finite and >= 0";
  }
  if (why) *why = os.str();
  return os.str().empty();
}

std::vector<CellClass> ComputeCost(const CostOptions& options, GridMap* grid) {
  const std::vector<float>& slope = grid->Layer(layers::kSlope);
  const std::vector<float>& roughness = grid->Layer(layers::kRoughness);
  const std::vector<float>& step = grid->Layer(layers::kStep);
  const std::vector<float>& elevation = grid->Layer(layers::kElevation);
  const GridGeometry& g = grid->geometry();
  std::vector<float>& cost = grid->AddLayer(layers::kCost, kNoData);
  std::vector<float>& class_layer = grid->AddLayer(layers::kClass, 0.f);
  const double weight_sum = options.slope_weight + options.step_weight + options.roughness_weight;
  std::vector<CellClass> classes(cost.size(), CellClass::kUnknown);
  for (std::size_t cell = 0; cell < cost.size(); ++cell) {
    if (std::isnan(slope[cell]) || std::isnan(roughness[cell]) || std::isnan(step[cell])) continue;
    const double s = slope[cell] / options.max_slope_deg;
    const double r = roughness[cell] / options.max_roughness_m;
    const double h = step[cell] / options.max_step_m;
    const bool steep_grade =
        options.lethal_on_cell_grade && CellGradeDeg(g, elevation, cell) > options.max_slope_deg;
    if (s > 1.0 || r > 1.0 || h > 1.0 || steep_grade) {
      cost[cell] = 1.f;
      classes[cell] = CellClass::kLethal;
    } else {
      cost[cell] = static_cast<float>(
          (options.slope_weight * s + options.roughness_weight * r + options.step_weight * h) /
          weight_sum);
      classes[cell] = cost[cell] < options.free_cost_max ? CellClass::kFree : CellClass::kCost;
    }
    class_layer[cell] = static_cast<float>(classes[cell]);
  }
  return classes;
}

ObstacleSummary MarkObstacles(const PointCloud& objects_local, const CostOptions& options,
                              GridMap* grid, std::vector<CellClass>* classes) {
  const GridGeometry& g = grid->geometry();
  HYLO_CHECK(classes->size() == g.NumCells(), "one class per cell");
  const std::vector<float>& elevation = grid->Layer(layers::kElevation);
  std::vector<float>& count = grid->AddLayer(kObstaclePoints, 0.f);
  const int max_ring =
      static_cast<int>(std::floor(options.ground_search_radius_m / g.resolution_m));
  std::vector<float> ground(g.NumCells(), kNoData);
  std::vector<char> ground_known(g.NumCells(), 0);  // cache: GroundHeight is a ring search
  ObstacleSummary summary;
  for (const Eigen::Vector3f& p : objects_local) {
    const auto cell = p.allFinite() ? g.CellOfLocal(p.x(), p.y()) : std::nullopt;
    if (!cell) continue;
    const std::size_t i = g.Index(cell->x(), cell->y());
    if (!ground_known[i]) {
      ground[i] = GroundHeight(g, elevation, cell->x(), cell->y(), max_ring);
      ground_known[i] = 1;
    }
    if (std::isnan(ground[i])) {
      ++summary.points_without_ground;
      continue;
    }
    const double height = p.z() - ground[i];
    if (height < options.obstacle_min_height_m) {
      ++summary.points_below_band;
    } else if (height > options.obstacle_max_height_m) {
      ++summary.points_above_band;
    } else {
      ++summary.points_in_band;
      count[i] += 1.f;
    }
  }
  std::vector<float>& cost = grid->MutableLayer(layers::kCost);
  std::vector<float>& class_layer = grid->MutableLayer(layers::kClass);
  for (std::size_t i = 0; i < g.NumCells(); ++i) {
    if (count[i] < options.min_obstacle_points) continue;
    ++summary.lethal_cells;
    (*classes)[i] = CellClass::kLethal;
    cost[i] = 1.f;
    class_layer[i] = static_cast<float>(CellClass::kLethal);
  }
  return summary;
}

}  // namespace hylo::terrain
