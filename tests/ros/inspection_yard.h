#pragma once
// A small yard for the ~plan_inspection tests, as files in the map frame, shifted by a
// UTM-like offset: flat ground 30 x 20 m (a point every 0.1 m), a 3 m wall at x = 12 (y 0..14),
// the costmap `hylo traversability` would write for it, and two targets, one in the open and
// one behind the wall (seen around its end).

#include <Eigen/Core>
#include <string>

namespace hylo::testing {

struct InspectionYard {
  std::string map, costmap_dir, targets;             ///< crafted map, costmap folder, targets CSV
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  ///< added to every coordinate, m
};

/// Writes the yard into `dir`.
InspectionYard WriteInspectionYard(const std::string& dir, const Eigen::Vector3d& offset);

}  // namespace hylo::testing
