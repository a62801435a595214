#include "hylo/terrain/ground_smrf_raster.h"

#include <algorithm>
#include <limits>

#include "hylo/common/check.h"

namespace hylo::terrain::smrf {
namespace {

// Lower cell index and weight of the upper one for linear interpolation between cell centres
// along one axis of `count` cells; `u` is the coordinate in cells from the grid origin.
void Bracket(double u, int count, int* lower, int* upper, double* weight) {
  const double centred = u - 0.5;
  const double floor_u = std::floor(centred);
  int i0 = static_cast<int>(floor_u);
  double w = centred - floor_u;
  if (i0 < 0) {
    i0 = 0;
    w = 0.0;
  } else if (i0 >= count - 1) {
    i0 = count - 1;
    w = 0.0;
  }
  *lower = i0;
  *upper = std::min(i0 + 1, count - 1);
  *weight = w;
}

}  // namespace

void Raster::CellOf(float x, float y, int* col, int* row) const {
  const double u = (static_cast<double>(x) - origin_xy.x()) / cell_m;
  const double v = (static_cast<double>(y) - origin_xy.y()) / cell_m;
  *col = std::clamp(static_cast<int>(std::floor(u)), 0, cols - 1);
  *row = std::clamp(static_cast<int>(std::floor(v)), 0, rows - 1);
}

double Raster::Sample(double x, double y) const {
  int c0, c1, r0, r1;
  double wx, wy;
  Bracket((x - origin_xy.x()) / cell_m, cols, &c0, &c1, &wx);
  Bracket((y - origin_xy.y()) / cell_m, rows, &r0, &r1, &wy);
  const double bottom = (1.0 - wx) * z[Index(c0, r0)] + wx * z[Index(c1, r0)];
  const double top = (1.0 - wx) * z[Index(c0, r1)] + wx * z[Index(c1, r1)];
  return (1.0 - wy) * bottom + wy * top;
}

PairRaster::PairRaster(const Raster& first, const Raster& second) {
  HYLO_CHECK(first.cols == second.cols && first.rows == second.rows, "one geometry");
  geometry_ = first;
  geometry_.z.clear();
  values_.resize(first.Size());
  for (std::size_t i = 0; i < values_.size(); ++i) values_[i] = {first.z[i], second.z[i]};
}

Eigen::Vector2d PairRaster::Sample(double x, double y) const {
  const Raster& g = geometry_;
  int c0, c1, r0, r1;
  double wx, wy;
  Bracket((x - g.origin_xy.x()) / g.cell_m, g.cols, &c0, &c1, &wx);
  Bracket((y - g.origin_xy.y()) / g.cell_m, g.rows, &r0, &r1, &wy);
  const auto at = [&](int c, int r) { return values_[g.Index(c, r)].cast<double>(); };
  const Eigen::Vector2d bottom = (1.0 - wx) * at(c0, r0) + wx * at(c1, r0);
  const Eigen::Vector2d top = (1.0 - wx) * at(c0, r1) + wx * at(c1, r1);
  return (1.0 - wy) * bottom + wy * top;
}

double CoveringCellCount(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy,
                         double cell_m) {
  const Eigen::Vector2d extent = (max_xy - min_xy) / cell_m;
  return (std::floor(extent.x()) + 1.0) * (std::floor(extent.y()) + 1.0);
}

Raster CoveringRaster(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, double cell_m) {
  HYLO_CHECK(cell_m > 0.0 && (max_xy - min_xy).minCoeff() >= 0.0, "a box and a cell size");
  Raster raster;
  raster.origin_xy = min_xy;
  raster.cell_m = cell_m;
  raster.cols = static_cast<int>(std::floor((max_xy.x() - min_xy.x()) / cell_m)) + 1;
  raster.rows = static_cast<int>(std::floor((max_xy.y() - min_xy.y()) / cell_m)) + 1;
  raster.z.assign(raster.Size(), std::numeric_limits<float>::quiet_NaN());
  return raster;
}

std::size_t FillMinimumSurface(const PointCloud& points, Raster* raster,
                               std::vector<Eigen::Vector2f>* lowest_offset_m) {
  if (lowest_offset_m) lowest_offset_m->assign(raster->Size(), Eigen::Vector2f::Zero());
  std::size_t filled = 0;
  for (const Eigen::Vector3f& p : points) {
    if (!p.allFinite()) continue;
    int col, row;
    raster->CellOf(p.x(), p.y(), &col, &row);
    const std::size_t i = raster->Index(col, row);
    float& z = raster->z[i];
    if (std::isnan(z)) {
      ++filled;
    } else if (z <= p.z()) {
      continue;
    }
    z = p.z();
    if (lowest_offset_m) {
      const Eigen::Vector2d centre =
          raster->origin_xy + raster->cell_m * Eigen::Vector2d(col + 0.5, row + 0.5);
      (*lowest_offset_m)[i] = (p.head<2>().cast<double>() - centre).cast<float>();
    }
  }
  return filled;
}

Eigen::Vector2d GradientPerCell(const Raster& dem, int col, int row) {
  const auto difference = [&dem](int a_col, int a_row, int b_col, int b_row) {
    const int steps = std::abs(b_col - a_col) + std::abs(b_row - a_row);
    if (steps == 0) return 0.0;
    return (static_cast<double>(dem.z[dem.Index(b_col, b_row)]) - dem.z[dem.Index(a_col, a_row)]) /
           steps;
  };
  return {difference(std::max(col - 1, 0), row, std::min(col + 1, dem.cols - 1), row),
          difference(col, std::max(row - 1, 0), col, std::min(row + 1, dem.rows - 1))};
}

Raster SlopeOf(const Raster& dem) {
  Raster slope = dem;
  for (int row = 0; row < dem.rows; ++row) {
    for (int col = 0; col < dem.cols; ++col) {
      const double rise_per_cell = GradientPerCell(dem, col, row).norm();
      slope.z[slope.Index(col, row)] = static_cast<float>(rise_per_cell / dem.cell_m);
    }
  }
  return slope;
}

}  // namespace hylo::terrain::smrf
