#pragma once
// Traversability cost of grid cells from their slope, roughness and step height, normalised
// by the vehicle's limits, and obstacles from object points (the non-ground part of a map)
// at heights that matter for the vehicle above the local ground.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/terrain/grid_map.h"

namespace hylo::terrain {

enum class CellClass : uint8_t {
  kUnknown = 0,  ///< no ground data (or too little for a plane)
  kFree = 1,     ///< cost below CostOptions::free_cost_max
  kCost = 2,     ///< traversable at a cost
  kLethal = 3,   ///< beyond a vehicle limit, or an obstacle
};
inline constexpr int kNumCellClasses = 4;
/// "unknown", "free", "cost", "lethal".
const char* CellClassName(CellClass cell_class);

struct CostOptions {
  double max_slope_deg = 20.0;          ///< vehicle limit: cells steeper than this are lethal, deg
  double max_step_m = 0.2;              ///< vehicle limit: higher steps are lethal, m
  double max_roughness_m = 0.1;         ///< vehicle limit: rougher cells are lethal, m
  bool lethal_on_cell_grade = true;     ///< also lethal when the elevation gradient at the
                                        ///< cell's own scale (central differences to the
                                        ///< neighbouring cells) exceeds max_slope_deg: a bank
                                        ///< narrower than the footprint plane fit
                                        ///< (SurfaceOptions::normal_radius_m) is not smoothed
                                        ///< away
  double slope_weight = 0.5;            ///< weight of slope / max_slope in the cost (>= 0)
  double step_weight = 0.25;            ///< weight of step / max_step in the cost (>= 0)
  double roughness_weight = 0.25;       ///< weight of roughness / max_roughness (>= 0); the three
                                        ///< weights are divided by their sum
  double free_cost_max = 0.3;           ///< cells with a cost below this are free, else cost, 0..1
  double obstacle_min_height_m = 0.2;   ///< object points lower than this above the local
                                        ///< ground are ignored (grass, ground noise), m
  double obstacle_max_height_m = 2.0;   ///< object points higher than this above the ground
                                        ///< are ignored (wires, canopy the vehicle passes
                                        ///< under), m
  int min_obstacle_points = 2;          ///< object points in that band a cell needs to become
                                        ///< lethal (one stray return is noise)
  double ground_search_radius_m = 3.0;  ///< a cell without elevation (under an object) takes
                                        ///< its ground from the nearest ring of cells with
                                        ///< elevation within this distance, m

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

struct ObstacleSummary {
  std::size_t points_in_band = 0;         ///< object points within the height band
  std::size_t points_below_band = 0;      ///< lower than obstacle_min_height_m
  std::size_t points_above_band = 0;      ///< higher than obstacle_max_height_m
  std::size_t points_without_ground = 0;  ///< no ground within ground_search_radius_m
  std::size_t lethal_cells = 0;           ///< cells made lethal by obstacles
};

/// Writes layers::kCost (0..1, NaN = unknown) and layers::kClass, and returns the classes.
/// Needs kSlope, kRoughness and kStep (ComputeSurfaceLayers). A cell whose slope, roughness
/// or step exceeds its limit, or whose cell-scale grade exceeds max_slope_deg (with
/// lethal_on_cell_grade), is lethal (cost 1); otherwise cost = weighted mean of the three
/// normalised values.
std::vector<CellClass> ComputeCost(const CostOptions& options, GridMap* grid);

/// Marks cells lethal where at least min_obstacle_points object points lie within the height
/// band above the local ground (layers::kElevation). Writes layers "obstacle_points" (count
/// in band), updates kCost/kClass and `classes`.
ObstacleSummary MarkObstacles(const PointCloud& objects_local, const CostOptions& options,
                              GridMap* grid, std::vector<CellClass>* classes);

}  // namespace hylo::terrain
