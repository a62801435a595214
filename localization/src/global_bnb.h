#pragma once
// The global localizer's branch and bound (global_localizer.h, step 1), kept out of the public
// header: the discretised scan and the search over (yaw, x, y).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/localization/global_localizer.h"
#include "hylo/localization/global_map.h"

namespace hylo::localization::internal {

/// Scan voxels sharing one map cell at one yaw: the cell offset from the vehicle's cell and
/// the mask of their height bins relative to the vehicle's ground.
struct ScanColumn {
  int32_t dx = 0;
  int32_t dy = 0;
  uint64_t bins = 0;
};

/// The levelled scan at every sampled yaw.
struct DiscreteScan {
  std::vector<double> yaws_rad;
  std::vector<std::vector<ScanColumn>> columns;  ///< per yaw, in map memory order (dy, dx)
  /// Per yaw, per column: the voxels of that column and every later one (the most the rest of
  /// a score can add).
  std::vector<std::vector<int>> voxels_from;
  int total_voxels = 0;  ///< voxels at yaw 0 (the score's denominator)
  /// Bin j of a column holds heights [(j - kGroundBin) z_bin, (j - kGroundBin + 1) z_bin)
  /// above the vehicle's ground.
  static constexpr int kGroundBin = 24;
};

/// `points_ground`: levelled scan points relative to the vehicle's ground under the sensor
/// (z = height above it), already filtered by range and clearance.
DiscreteScan Discretize(const PointCloud& points_ground, const GlobalMapOptions& map_options,
                        double yaw_step_rad);

/// Height of the ground under the sensor in `levelled` (the scan rotated level, sensor at
/// the origin, m): the plane through each azimuth sector's lowest returns within 10 m, sectors
/// off the plane dropped, read at the sensor's xy. False when no sector holds enough returns.
bool GroundUnderSensor(const PointCloud& levelled, double* ground_z);

/// CPU time of the calling thread, s: the localizer's figures are per core, not inflated by
/// other work on a shared machine.
double ThreadCpuSeconds();

/// One pose of the search: yaw sample, the vehicle's cell, its score in voxels.
struct BnbCandidate {
  int yaw_index = 0;
  int32_t x = 0;
  int32_t y = 0;
  int score = 0;
};

struct BnbOptions {
  int max_candidates = 8;
  int min_score = 1;  ///< voxels
  double z_tolerance_m = 0.3;
  double distinct_cells = 4.0;  ///< translation distinctness, cells
  double distinct_yaw_rad = 0.17;
};

/// The best `max_candidates` mutually distinct poses scoring >= min_score, best first.
/// `nodes_scored` receives the number of bounds computed, `columns_scored` the scan columns
/// they looked at (the search's work, whatever else the machine runs).
std::vector<BnbCandidate> BranchAndBound(const DiscreteScan& scan, const GlobalMap& map,
                                         const BnbOptions& options, std::size_t* nodes_scored,
                                         std::size_t* columns_scored = nullptr);

/// Score of one pose at pyramid level `level` (level 0: the exact score; level k: an upper
/// bound over the 2^k x 2^k positions starting at (x, y)); -1 when no cell of the block has
/// ground (no vehicle can stand there). A score that cannot exceed `cutoff` stops early and
/// returns a value <= cutoff (the caller prunes it either way).
int ScoreNode(const DiscreteScan& scan, const GlobalMap& map, int yaw_index, int32_t x, int32_t y,
              int level, double z_tolerance_m, int cutoff = -1,
              std::size_t* columns_scored = nullptr);

}  // namespace hylo::localization::internal
