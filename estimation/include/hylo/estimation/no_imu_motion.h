#pragma once
// What every back-end does without an IMU (section `no_imu:` of a run configuration): a
// constant-velocity motion model learnt from the last two poses, and a yaw search that starts
// the update from the heading with the most plane matches, because a hand-held sensor at a low
// scan rate turns more between scans than plane association recovers from.

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>

#include "hylo/estimation/nav_state.h"

namespace hylo::estimation {

struct NoImuOptions {
  double cv_translation_noise = 1.0;  ///< random walk on the velocity, m/s/√s (> 0)
  double cv_rotation_noise = 0.5;     ///< random walk on the body rate, rad/s/√s (> 0)
  /// Before iterating, try yaw offsets about the map z axis within ±this of the constant-
  /// velocity prediction and start from the one with most plane matches, deg ([0, 180];
  /// 0 = off).
  double yaw_search_deg = 0.0;
  double yaw_search_step_deg = 5.0;  ///< step of that search, deg (> 0)

  bool IsValid(std::string* why) const;
};

/// The constant-velocity model: the pose moves on with the velocity and body rate of the last
/// update interval.
class ConstantVelocity {
 public:
  /// Body rate of the last interval, rad/s (IMU frame).
  const Eigen::Vector3d& omega_imu() const { return omega_imu_; }
  void Reset() { omega_imu_.setZero(); }
  /// After an update that moved the state from `before` to `*after`: sets after->v_map_imu and
  /// the body rate from the two poses (nothing when no time passed).
  void Learn(const NavState& before, NavState* after);

 private:
  Eigen::Vector3d omega_imu_ = Eigen::Vector3d::Zero();
};

/// The yaw search: `prior` turned about the map z axis by offsets within ±yaw_search_deg in
/// steps of yaw_search_step_deg; returns the candidate for which `count_matches` is largest
/// (`prior` itself on ties at zero).
NavState SearchYaw(const NavState& prior, const NoImuOptions& options,
                   const std::function<std::size_t(const NavState&)>& count_matches);

}  // namespace hylo::estimation
