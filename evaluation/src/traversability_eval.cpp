#include "hylo/evaluation/traversability_eval.h"

#include <cmath>

#include "hylo/common/check.h"

namespace hylo::evaluation {
namespace {

bool HasData(const terrain::GridMap& grid, std::size_t cell, CellSelection selection) {
  if (selection == CellSelection::kAnyValue) return true;
  return grid.HasLayer(terrain::layers::kPointCount) &&
         grid.Layer(terrain::layers::kPointCount)[cell] > 0.f;
}

}  // namespace

LayerComparison CompareLayer(const terrain::GridMap& grid, const std::string& layer,
                             const TruthField& truth, CellSelection selection) {
  const terrain::GridGeometry& g = grid.geometry();
  const std::vector<float>& values = grid.Layer(layer);
  LayerComparison result;
  double sum = 0.0, sum_sq = 0.0;
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    if (std::isnan(values[cell]) || !HasData(grid, cell, selection)) continue;
    const Eigen::Vector2d xy = g.CentreWorld(g.Col(cell), g.Row(cell));
    const double expected = truth(xy.x(), xy.y());
    if (!std::isfinite(expected)) continue;
    const double error = values[cell] - expected;
    ++result.cells;
    sum += error;
    sum_sq += error * error;
    result.max_abs_error = std::max(result.max_abs_error, std::abs(error));
  }
  if (result.cells > 0) {
    result.mean_error = sum / result.cells;
    result.rmse = std::sqrt(sum_sq / result.cells);
  }
  return result;
}

TruthField SampleLayer(const terrain::GridMap& truth_grid, const std::string& layer) {
  const terrain::GridGeometry g = truth_grid.geometry();
  const std::vector<float> values = truth_grid.Layer(layer);
  return [g, values](double x_world, double y_world) {
    const auto cell = g.CellOfLocal(x_world - g.origin_world.x(), y_world - g.origin_world.y());
    if (!cell) return std::nan("");
    return static_cast<double>(values[g.Index(cell->x(), cell->y())]);
  };
}

SteepCellCheck CheckSteepCells(const terrain::GridMap& grid,
                               const std::vector<terrain::CellClass>& classes,
                               const TruthField& true_slope_deg, double max_slope_deg) {
  const terrain::GridGeometry& g = grid.geometry();
  HYLO_CHECK(classes.size() == g.NumCells(), "one class per cell");
  const std::vector<float>& slope = grid.Layer(terrain::layers::kSlope);
  SteepCellCheck check;
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    if (!HasData(grid, cell, CellSelection::kMeasured)) continue;
    const Eigen::Vector2d xy = g.CentreWorld(g.Col(cell), g.Row(cell));
    const double truth = true_slope_deg(xy.x(), xy.y());
    if (!(truth > max_slope_deg)) continue;
    if (std::isnan(slope[cell])) {
      ++check.steep_unknown;
      continue;
    }
    ++check.steep_cells;
    if (classes[cell] == terrain::CellClass::kLethal) ++check.marked_lethal;
  }
  check.fraction_marked =
      check.steep_cells == 0 ? 1.0 : static_cast<double>(check.marked_lethal) / check.steep_cells;
  return check;
}

}  // namespace hylo::evaluation
