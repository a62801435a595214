#pragma once
// Workload 3 of the map benchmark: a lidar-like run. Per step: 5-NN (max 5 m) for every scan
// point against the map as it stands (what registration does), then insert the scan with
// 0.5 m on-tree downsampling, then delete one box (the slab of map left `window_m` behind).
// The static trees are rebuilt from the same map content, as their user must after every
// change; to keep the run short they are measured every `static_every` steps.

#include "benchmark_common.h"

namespace hylo::benchmarks {

struct LidarRunConfig {
  int steps = 2000;         ///< scans
  int scan_points = 2000;   ///< points per scan (inserted and queried)
  float voxel_m = 0.5f;     ///< on-tree downsampling voxel edge, m
  float window_m = 1300.f;  ///< map kept behind the sensor, m (sets the ~500k plateau)
  int static_every = 50;    ///< steps between static-tree measurements
};

struct LidarRunResult {
  double ikd_step_ms_at_max = 0;        ///< mean ikd step over steps with map >= 90% of max
  double static_rebuild_ms_at_max = 0;  ///< mean nanoflann rebuild at those map sizes
  double pcl_rebuild_ms_at_max = 0;     ///< mean PCL rebuild at those map sizes
  double ikd_bytes_per_point = 0;       ///< IkdTree::MemoryBytes / Size at the end
};

LidarRunResult RunLidar(const LidarRunConfig& config, Report* report);

}  // namespace hylo::benchmarks
