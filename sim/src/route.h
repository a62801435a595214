#pragma once
// A drivable path through waypoints (straight runs, corners rounded by quadratic Bezier
// arcs) sampled densely, with a time-optimal speed profile under acceleration, lateral
// acceleration and cruise limits (forward/backward passes), starting and ending at rest.

#include <Eigen/Core>
#include <vector>

#include "hylo/sim/trajectory.h"

namespace hylo::sim {

class RoutePlan {
 public:
  RoutePlan(const std::vector<Eigen::Vector2d>& waypoints_m, const TrajectoryOptions& options);

  /// Where the vehicle is `t_s` seconds after it starts moving (clamped to the route end).
  void Sample(double t_s, Eigen::Vector2d* xy_m, double* heading_rad, double* speed_mps,
              double* distance_m) const;
  double length_m() const { return s_.back(); }
  double duration_s() const { return t_.back(); }

 private:
  std::vector<Eigen::Vector2d> xy_;
  std::vector<double> s_, t_, heading_, speed_;
};

}  // namespace hylo::sim
