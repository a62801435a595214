#pragma once
// Reads a ROS map_server map (YAML + PGM), as `hylo traversability` writes it
// (hylo/io/costmap_io.h), into the cells of a nav_msgs/OccupancyGrid, with map_server's own
// semantics so that a planner sees the same grid from this node as from map_server:
//   occupancy p = (255 - pixel) / 255 (negate: 0), or pixel / 255 (negate: 1);
//   mode trinary: p > occupied_thresh → 100, p < free_thresh → 0, else -1 (unknown);
//   mode scale:   the same ends, 99·(p - free)/(occupied - free) in between;
//   mode raw:     the pixel value itself (hylo's graded cost greys survive only here).
// No ROS type: unit-tested against io::WriteMapServer without a master.

#include <cstdint>
#include <string>
#include <vector>

namespace hylo::rosnode {

struct OccupancyGridData {
  double resolution_m = 0.0;    ///< cell side, m
  int width = 0;                ///< cells along x
  int height = 0;               ///< cells along y
  double origin_x_m = 0.0;      ///< world position of the lower-left cell's corner, m
  double origin_y_m = 0.0;      ///< m
  double origin_yaw_rad = 0.0;  ///< rad
  std::vector<int8_t> cells;    ///< row-major, row 0 = lowest y (OccupancyGrid order);
                                ///< 0..100 occupancy, -1 unknown
};

/// Reads `yaml_path` and the image it names (relative to the YAML's folder). Throws
/// std::runtime_error naming the file and the reason (missing key, unreadable or malformed
/// PGM, unsupported mode or image format).
OccupancyGridData ReadMapServerMap(const std::string& yaml_path);

}  // namespace hylo::rosnode
