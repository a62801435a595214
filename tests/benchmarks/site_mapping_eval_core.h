#pragma once
// The offline mapping chain measured on the simulated substation (the simulator's
// figures), shared by the hylo_site_mapping_eval program and the site_mapping_test:
//   1. session A's scans registered with the TRUE poses (each point at its own time), so the
//      map's thickness is sensor noise only; crafting (uniform sampling + MLS) measured by the
//      RMS distance to the simulator's exact surfaces, and timed on a 1M-point map;
//   2. the ground filter (the demo's: GroundFilterOptions::ForRobotMaps, or the back-end
//      chosen) against the hit surface of each return (ground / object);
//   3. traversability slope against the simulator's true slope grid (site_slope.txt).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/evaluation/traversability_eval.h"
#include "hylo/sim/simulator.h"
#include "hylo/terrain/craft.h"
#include "hylo/terrain/ground_filter.h"
#include "hylo/terrain/traversability.h"

namespace hylo::site_eval {

struct SiteEvalOptions {
  sim::SimulationOptions sim;        ///< site, session A length, lidar (seed included)
  int scan_stride = 1;               ///< accumulate every n-th scan of session A (>= 1)
  std::size_t thickness_samples = 2'000'000;  ///< raw points whose distance is measured
                                              ///< (evenly strided subset; 0 = all)
  terrain::CraftOptions craft;                ///< `hylo craft` defaults
  std::size_t timing_points = 1'000'000;  ///< map size for the 1- vs 2-thread timing (0 = skip)
  double ground_voxel_m = 0.1;       ///< one return per voxel before the ground filter, m
  terrain::GroundFilterOptions ground =  ///< the demo's (a run configuration's default)
      terrain::GroundFilterOptions::ForRobotMaps();
  terrain::TraversabilityOptions traversability;  ///< `hylo traversability` defaults
  std::string out_dir;               ///< site_slope.txt (and nothing else) is written here
  bool measure_craft = true;         ///< part 1 (crafting); false leaves CraftFigures empty
  bool measure_ground_and_slope = true;  ///< parts 2 and 3; false leaves their figures empty
  bool write_cell_tables = false;    ///< also write cells_<ground source>.csv to out_dir: one
                                     ///< row per cell with data (estimate, truths, counts) for
                                     ///< finding where the slope error sits

  bool IsValid(std::string* why) const;
};

/// Session A accumulated in the map frame with the true poses.
struct AccumulatedMap {
  std::vector<Eigen::Vector3d> points_map;  ///< m
  std::vector<uint8_t> is_ground;           ///< per point: the return hit the terrain
  std::vector<std::size_t> scan_begin;     ///< index of each scan's first point
  double simulate_seconds = 0.0;            ///< wall time of ray casting + registration, s
};

/// Distances of a cloud to the true surfaces.
struct Thickness {
  std::size_t points = 0;     ///< points measured
  double rms_m = 0.0;         ///< RMS distance ("thickness"), m
  double rms_ground_m = 0.0;  ///< of the points whose nearest surface is the ground, m
  double rms_object_m = 0.0;  ///< of the points nearest to a primitive, m
  double rms_thin_m = 0.0;    ///< of the points nearest to a primitive thinner than 0.1 m
                              ///< (cables, lattice beams, busbars), m
  double rms_thick_box_m = 0.0;       ///< of the points nearest to a thicker box, m
  double rms_thick_cylinder_m = 0.0;  ///< of the points nearest to a thicker cylinder, m
  double fraction_thin = 0.0;    ///< of the points measured, nearest to a thin primitive
  double fraction_ground = 0.0;  ///< of the points measured, nearest to the ground
  double p95_m = 0.0;         ///< 95th percentile distance, m
  double beyond_10cm = 0.0;   ///< fraction of points farther than 0.1 m
};

struct CraftFigures {
  Thickness raw, sampled, crafted;  ///< input map, after uniform sampling only, after MLS
  std::size_t crafted_points = 0;
  std::size_t sampled_points = 0;      ///< after uniform sampling (MLS input)
  std::size_t support_points = 0;      ///< points the MLS fits used (support + sampled)
  std::size_t small_scale_points = 0;  ///< crafted points that took the small MLS radius
  double seconds = 0.0;                ///< wall time of CraftMap on the whole map, s
  std::size_t timing_points = 0;       ///< size of the timed map
  double seconds_1_thread = 0.0;       ///< wall time (sampling + MLS), s
  double seconds_2_threads = 0.0;      ///< wall time (sampling + MLS), s
  double ThicknessRatio() const { return raw.rms_m / crafted.rms_m; }
};

/// Confusion of a ground filter against the truth; ISPRS definitions (shared/data/README.md).
struct GroundFigures {
  std::size_t ground_as_ground = 0, ground_as_object = 0;
  std::size_t object_as_ground = 0, object_as_object = 0;
  double seconds = 0.0;  ///< wall time of the filter, s
  std::string method;  ///< the ground back-end that ran
  double TypeI() const;   ///< ground rejected / ground
  double TypeII() const;  ///< objects accepted as ground / objects
  double Total() const;   ///< misclassified / all
  double Kappa() const;   ///< Cohen's kappa
};

struct SlopeFigures {
  evaluation::LayerComparison slope;  ///< slope (deg) on cells with data vs site_slope.txt
  evaluation::SteepCellCheck steep;   ///< cells truly steeper than the vehicle limit
  /// The same against the clean terrain's slope at the estimator's scale (FootprintSlope):
  /// site_slope.txt is the slope over one cell, the estimate that over the vehicle footprint,
  /// so part of the first comparison's error is the difference of scales, not estimation.
  evaluation::LayerComparison slope_footprint;
  evaluation::SteepCellCheck steep_footprint;
  std::size_t measured_cells = 0;
  std::size_t cells_at_data_edge = 0;  ///< cells left unknown at a data edge
  std::size_t cells_finer_scale = 0;   ///< cells whose normal came from a block, not the
                                       ///< footprint (adaptive scale)
  double noise_m = 0.0;                ///< SurfaceSummary::noise_m
  /// Cells with data that got a slope estimate: slope.cells / measured_cells.
  double Coverage() const {
    return measured_cells > 0 ? static_cast<double>(slope.cells) / measured_cells : 0.0;
  }
  double seconds = 0.0;
};

struct SiteFigures {
  AccumulatedMap map;  ///< kept so callers can inspect it
  CraftFigures craft;
  GroundFigures ground;
  std::size_t ground_filter_points = 0;
  SlopeFigures slope_filter;  ///< traversability from the ground filter's ground (the chain)
  SlopeFigures slope_truth;  ///< from the truly ground returns (isolates the grid's error)
  /// As slope_truth with SurfaceOptions::unknown_at_data_edge off: every cell estimated, so
  /// the price of the cells left unknown at data edges is on the table.
  SlopeFigures slope_truth_all_cells;
};

/// The short version (CI): the simulator's coarse settings (SimulationOptions::Fast) for a
/// 20 s session A, crafting timed on 200k points; everything else as in the full run.
SiteEvalOptions QuickOptions(const std::string& out_dir);

/// Every return of session A (every `scan_stride`-th scan) in the map frame.
AccumulatedMap AccumulateSessionA(const sim::SimulationOptions& options,
                                  const sim::Site& site, int scan_stride);

/// Runs the three measurements. Throws std::invalid_argument on invalid options.
SiteFigures EvaluateSite(const SiteEvalOptions& options);

/// True slope (deg) of the clean terrain (no gravel) at the vehicle's scale: the tilt of the
/// least-squares plane through its heights on a 0.1 m lattice within `radius_m` of (x, y).
evaluation::TruthField FootprintSlope(const sim::Site& site, double radius_m);

/// Reads the simulator's slope grid (reference_outputs.h format) as a field: the value of
/// the cell holding (x, y), NaN outside. Throws std::runtime_error naming the file.
evaluation::TruthField ReadSimSlopeGrid(const std::string& path);

}  // namespace hylo::site_eval
