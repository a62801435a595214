#pragma once
// Ground / object split by cloth simulation (CSF: Zhang et al., "An Easy-to-Use Airborne LiDAR
// Data Filtering Method Based on Cloth Simulation", Remote Sensing 2016, 8(6):501). The cloud
// is turned upside down, a cloth of particles falls onto it under gravity, held together by
// internal constraints; points close to the settled cloth are ground.
//
// The pieces live in separate headers, one idea each: cloth_filter_cloth.h (particle grid and
// its dynamics), cloth_filter_surface.h (the rasterised inverted surface the particles land
// on), cloth_filter_slope.h (slope post-processing). This header is the entry point.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hylo/terrain/ground_label.h"
#include "hylo/common/point_types.h"

namespace hylo::terrain {

/// How particles without a point under them (gaps, sparse data, a cloth finer than the point
/// spacing) get the height the cloth stops at.
enum class ClothHoleFill {
  kNeighbourMean,     ///< rings of holes take the mean of their known 4-neighbours (default;
                      ///< ISPRS mean total error at GR 1, RI 3: 6.09 %, nearest 6.67 %)
  kNearest,           ///< the height of the horizontally nearest measured particle, the paper's
                      ///< definition (each particle meets the nearest point under it); better
                      ///< when the cloth is finer than the point spacing (ISPRS at GR 0.5,
                      ///< RI 6: 4.25 %, mean 4.69 %), where the mean smooths a roof's edge
  kReferenceScanline  ///< as jianboqi/CSF: first measured particle along the row, then the
                      ///< column; extends a gap's edge flat across it
};

/// Defaults are the paper's / reference implementation's (GR 1, RI 3, dT 0.65, 500 iterations,
/// hcc 0.5, slope smoothing on). The paper's rule for the rigidness by scene: 1 for steep slopes
/// and rugged terrain, 2 for relief / terraced scenes, 3 for flat (urban) scenes.
struct ClothFilterOptions {
  double cloth_resolution_m = 1.0;  ///< paper GR: horizontal spacing of cloth particles, m (> 0)
  int rigidness = 3;         ///< paper RI: constraint passes per step, 1 soft .. 3 hard (1..10)
  double time_step = 0.65;   ///< paper dT: simulation time step, simulation units (> 0)
  int max_iterations = 500;  ///< simulation steps at most (>= 1)
  double class_threshold_m = 0.5;  ///< paper hcc: |point - cloth| below this is ground, m (> 0)
  bool class_distance_along_normal = true;  ///< measure |point - cloth| to the cloth surface
                                            ///< (vertical gap x cos of the cloth's tilt, the
                                            ///< geometric point-to-cloth distance); false: the
                                            ///< vertical gap, as the reference release does,
                                            ///< which grows as 1/cos(slope), so that ground
                                            ///< on steep terrain looks like objects
  bool slope_smoothing = true;  ///< paper ST: post-process movable particles on steep slopes
  double slope_height_threshold_m = 0.3;   ///< post-processing: a movable particle is pinned to
                                           ///< the surface when it continues a pinned neighbour
                                           ///< within this height, m (> 0)
  double slope_max_cloth_gap_m = 3.0;      ///< post-processing pins a particle only where the
                                           ///< settled cloth is closer than this to the surface
                                           ///< under it: a floating cloth on a slope, not one
                                           ///< spanning an object a storey or more high (a
                                           ///< bridge deck, ISPRS samp21), m (> 0; infinity =
                                           ///< no test, as the reference release)
  int slope_min_region_particles = 50;     ///< post-processing only touches movable regions of
                                           ///< more than this many particles (>= 0)
  double convergence_threshold_m = 0.005;  ///< stop when no particle moved more than this in one
                                           ///< step, m (>= 0; 0 = run all iterations)
  ClothHoleFill hole_fill = ClothHoleFill::kNeighbourMean;  ///< surface height under particles
                                                            ///< without a point of their own
  double low_outlier_depth_m = 3.0;       ///< points this far below nearly all their neighbours
                                          ///< are left out of the surface the cloth lands on (they
                                          ///< are still classified), m (>= 0; 0 = keep all)
  double low_outlier_cell_m = 10.0;       ///< neighbourhood for that test: 3x3 cells of this size,
                                          ///< wider than a cluster of multipath returns, m (> 0)
  int low_outlier_min_support = 3;        ///< a point needs this many neighbours within
                                          ///< low_outlier_depth_m of it to stay (>= 1)
  double low_outlier_max_fraction = 0.1;  ///< ... and at least this fraction of its neighbours
                                          ///< (a fraction holds at any point density; a
                                          ///< cluster of outliers supports itself by count),
                                          ///< [0, 1); 0 = the count alone
  double gravity = 0.2;   ///< downward acceleration in cloth units per step^2 (> 0); with dT 0.65
                          ///< a free particle falls 0.085 m in its first step. The reference
                          ///< release that produced csf_sample multiplies by dT^2 twice
                          ///< (0.2 * 0.65^2 here reproduces it); that stiffer cloth hangs on
                          ///< rough terrain, so the default keeps Eq. (3) as written
  double damping = 0.01;  ///< fraction of the previous step's velocity lost per step, [0, 1)

  /// False (with the field, its value and the constraint in *why) when a field is out of range.
  bool IsValid(std::string* why) const;
};

/// What the filter did. `labels` has one entry per input point, in input order.
struct ClothFilterResult {
  bool ok = false;                          ///< false: nothing classified, see message
  std::string message;                      ///< why not ok, or a one-line description
  std::vector<GroundLabel> labels;          ///< per input point: ground within
                                            ///< class_threshold_m of the cloth
  std::vector<float> height_above_cloth_m;  ///< per input point: z - cloth height under it, m
                                            ///< (NaN for invalid points); ground is |.| < hcc
  std::size_t num_ground = 0;
  std::size_t num_objects = 0;
  std::size_t num_invalid = 0;           ///< non-finite points (labelled kInvalid)
  int iterations = 0;                    ///< simulation steps run
  bool converged = false;                ///< stopped by convergence_threshold_m
  double last_max_displacement_m = 0.0;  ///< largest particle move in the last step, m
  int cloth_cols = 0;                    ///< particles along x
  int cloth_rows = 0;                    ///< particles along y
  std::size_t num_hole_particles = 0;    ///< particles with no point under them (filled)
  std::size_t num_pinned_by_slope = 0;   ///< particles pinned by slope post-processing
  std::size_t num_low_outliers = 0;      ///< points left out of the surface as low outliers
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();  ///< shift used to compute near zero
};

/// Called once per simulation step (iteration starts at 1).
using ClothProgress = std::function<void(int iteration, int max_iterations)>;

/// Classifies points given in world (possibly UTM) coordinates: an origin is chosen and kept
/// in the result, the work is done on coordinates near zero. Empty or all-NaN input gives
/// ok = false. Throws std::invalid_argument when options are invalid.
ClothFilterResult FilterGround(const std::vector<Eigen::Vector3d>& points_world,
                               const ClothFilterOptions& options,
                               const ClothProgress& progress = {});

/// The same on a cloud already near zero (origin_world stays zero).
ClothFilterResult FilterGroundLocal(const PointCloud& points_local,
                                    const ClothFilterOptions& options,
                                    const ClothProgress& progress = {});

}  // namespace hylo::terrain
