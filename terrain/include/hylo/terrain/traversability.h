#pragma once
// Ground points (+ optional object points) -> grid map -> traversability classes: the last
// step of the offline mapping chain (ARCHITECTURE.md). World coordinates come in as double; the
// work is done near zero around an origin kept in the grid geometry (local_origin.h).

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "hylo/terrain/grid_map.h"
#include "hylo/terrain/grid_map_elevation.h"
#include "hylo/terrain/grid_map_surface.h"
#include "hylo/terrain/traversability_cost.h"

namespace hylo::terrain {

struct TraversabilityOptions {
  double resolution_m = 0.2;         ///< grid cell edge, m
  std::size_t max_cells = 50000000;  ///< refuse larger grids (memory guard), cells
  ElevationOptions elevation;        ///< elevation and hole filling
  SurfaceOptions surface;            ///< normals, slope, roughness, step
  CostOptions cost;                  ///< vehicle limits, weights, obstacles

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

struct SlopeStats {
  std::size_t cells = 0;  ///< cells with a slope
  double mean_deg = 0.0;
  double median_deg = 0.0;
  double p95_deg = 0.0;  ///< 95th percentile
  double max_deg = 0.0;
};

struct TraversabilitySummary {
  std::size_t ground_points = 0;          ///< points given
  std::size_t ground_points_skipped = 0;  ///< non-finite
  std::size_t object_points = 0;          ///< points given
  std::size_t object_points_skipped = 0;  ///< non-finite
  ElevationSummary elevation;
  SurfaceSummary surface;
  ObstacleSummary obstacles;
  std::array<std::size_t, kNumCellClasses> cells_per_class{};  ///< indexed by CellClass
  SlopeStats slope;
};

struct TraversabilityMap {
  GridMap grid;                    ///< layers named in grid_map.h `layers::`
  std::vector<CellClass> classes;  ///< one per cell
  TraversabilitySummary summary;
};

/// Called at the start of each stage ("binning", "elevation", "surface", "cost",
/// "obstacles"), so a command line can show progress.
using StageCallback = std::function<void(const std::string& stage, int index, int count)>;

/// Builds the traversability map. Throws std::invalid_argument when `options` are not valid
/// (the IsValid reason), std::runtime_error when the ground cloud has no finite point or the
/// grid would be too large. Non-finite points are skipped and counted.
TraversabilityMap ComputeTraversability(const std::vector<Eigen::Vector3d>& ground_world,
                                        const std::vector<Eigen::Vector3d>& objects_world,
                                        const TraversabilityOptions& options,
                                        const StageCallback& on_stage = {});

SlopeStats ComputeSlopeStats(const std::vector<float>& slope_deg);

}  // namespace hylo::terrain
