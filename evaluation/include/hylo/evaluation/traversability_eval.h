#pragma once
// Evaluation of grid layers against a known truth: an analytic surface in tests, the
// simulator's true slope grid for the site-level figures. The truth is a field sampled at
// world xy, so grids of any origin and resolution can be compared.

#include <cstddef>
#include <functional>
#include <string>

#include "hylo/terrain/grid_map.h"
#include "hylo/terrain/traversability_cost.h"

namespace hylo::evaluation {

/// A truth value at a world position; NaN where the truth has none.
using TruthField = std::function<double(double x_world, double y_world)>;

/// Which cells are compared.
enum class CellSelection {
  kMeasured,  ///< cells with ground points (terrain::layers::kPointCount > 0): "cells with data"
  kAnyValue,  ///< every cell whose layer value is finite (includes hole-filled cells)
};

struct LayerComparison {
  std::size_t cells = 0;    ///< cells compared (estimate and truth finite)
  double rmse = 0.0;        ///< root mean square of estimate - truth, layer units
  double mean_error = 0.0;  ///< mean of estimate - truth (bias)
  double max_abs_error = 0.0;
};

/// Compares `layer` at each selected cell centre with `truth` there.
LayerComparison CompareLayer(const terrain::GridMap& grid, const std::string& layer,
                             const TruthField& truth,
                             CellSelection selection = CellSelection::kMeasured);

/// Slope RMSE in degrees on cells with data (CompareLayer on terrain::layers::kSlope).
inline LayerComparison CompareSlope(const terrain::GridMap& grid,
                                    const TruthField& true_slope_deg) {
  return CompareLayer(grid, terrain::layers::kSlope, true_slope_deg);
}

/// The truth from another grid (e.g. the simulator's slope grid read by io::ReadAsciiGrid):
/// the value of the cell containing the position, NaN outside or on no data. The grid is
/// copied into the returned function.
TruthField SampleLayer(const terrain::GridMap& truth_grid, const std::string& layer);

struct SteepCellCheck {
  std::size_t steep_cells = 0;    ///< cells with a slope estimate whose true slope exceeds
                                  ///< the limit
  std::size_t marked_lethal = 0;  ///< of those, classed lethal
  double fraction_marked = 0.0;   ///< marked_lethal / steep_cells (1 when none are steep)
  std::size_t steep_unknown = 0;  ///< cells with ground points but no slope estimate (too
                                  ///< few points) whose true slope exceeds the limit; not in
                                  ///< steep_cells, reported so they are not hidden
};

/// Among cells with a slope estimate (the "cells with data" of CompareSlope) whose true slope
/// exceeds `max_slope_deg`, how many are marked non-traversable (lethal). Measured cells left
/// without a slope are counted apart (steep_unknown): an unknown cell is not a wrong slope, a
/// planner treats it as unexplored.
SteepCellCheck CheckSteepCells(const terrain::GridMap& grid,
                               const std::vector<terrain::CellClass>& classes,
                               const TruthField& true_slope_deg, double max_slope_deg);

}  // namespace hylo::evaluation
