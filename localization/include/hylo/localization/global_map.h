#pragma once
// What the global localizer precomputes once per prior map: a 2.5-D occupancy raster of the
// map and its branch-and-bound pyramid (Hess et al., "Real-time loop closure in 2D LIDAR
// SLAM", ICRA 2016, Sec. V-C, with a height profile per cell instead of a probability).
//
// Level 0: per xy cell of `cell_m`, a 64-bit mask of the height bins (`z_bin_m` each, from
// z0 upwards) that hold map points, and the lowest map point of the cell (the ground a vehicle
// standing in that cell would stand on). Level k: per cell, the OR of the masks and the
// min/max of the ground over the 2^k x 2^k cells starting at it, so one lookup bounds the
// score of every translation in a block of 2^k x 2^k cells (the "precomputation grids").
// Everything is in the prior map's local frame (metres, z up).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"

namespace hylo::localization {

struct GlobalMapOptions {
  double cell_m = 0.5;   ///< xy cell of the raster, m: the search's position step, > 0
  double z_bin_m = 0.5;  ///< height bin of a cell's profile, m (64 bins cover 64 x this), > 0
  int levels = 7;        ///< pyramid levels: the coarsest block is 2^(levels-1) cells, [1, 12]
  double max_cells_million = 64.0;  ///< larger rasters are refused (memory), million cells, > 0

  bool IsValid(std::string* why) const;
};

class GlobalMap {
 public:
  static constexpr int kZBins = 64;

  /// One level of the pyramid, row-major (index = y * width + x).
  struct Level {
    std::vector<uint64_t> occupancy;  ///< OR of the height masks over the cell's block
    std::vector<float> ground_min_m;  ///< lowest cell ground over the block, m (+inf: none)
    std::vector<float> ground_max_m;  ///< highest cell ground over the block, m (-inf: none)
  };

  /// Where the raster lies and what it was built from.
  struct Layout {
    GlobalMapOptions options;
    float origin_x_m = 0.f;  ///< local x of the raster's corner (cell 0 starts here), m
    float origin_y_m = 0.f;  ///< local y of the corner, m
    float z0_m = 0.f;        ///< bottom of height bin 0, m
    int32_t width = 0;       ///< cells along x
    int32_t height = 0;      ///< cells along y
    uint64_t num_points = 0;       ///< map points rasterised
    uint64_t num_points_above = 0; ///< points above the 64 bins (left out of the masks)
  };

  GlobalMap() = default;

  /// Rasterises `points_map` (local frame). Throws std::invalid_argument naming the reason
  /// when there is no finite point, the options are invalid or the raster would exceed
  /// options.max_cells_million.
  static GlobalMap Build(const PointCloud& points_map, const GlobalMapOptions& options);

  const Layout& layout() const { return layout_; }
  const GlobalMapOptions& options() const { return layout_.options; }
  int num_levels() const { return static_cast<int>(levels_.size()); }
  const Level& level(int k) const { return levels_[static_cast<std::size_t>(k)]; }
  bool empty() const { return levels_.empty(); }
  /// Bytes held by the pyramid.
  std::size_t MemoryBytes() const;
  /// Height bin of `z_m` (may be outside [0, kZBins)).
  int ZBin(double z_m) const;

 private:
  Layout layout_;
  std::vector<Level> levels_;
};

}  // namespace hylo::localization
