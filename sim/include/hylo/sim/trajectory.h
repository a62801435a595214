#pragma once
// The vehicle's ground-truth motion: the pose of the IMU frame in the map, T_map_imu(t).
//
// How it is made (and why it is exact): waypoints are joined by straight runs and rounded
// corners; a speed profile (standstill, then acceleration-, lateral-acceleration- and
// cruise-limited) gives the position along that path at every knot time; at each knot the
// vehicle's attitude comes from the smooth terrain under its four wheels (pitch from front vs
// rear, roll from left vs right) plus suspension jitter that grows with speed. These knot
// values of (x, y, z, yaw, pitch, roll) become the control points of six uniform cubic
// B-splines in time. The splines *are* the truth: C2, with analytic first and second
// derivatives, so velocity, acceleration and body rates (ZYX Euler rates mapped to the body)
// are exact, and integrating the IMU derived from them reproduces the trajectory.
// The first `standstill_s` are exactly at rest (identical control points).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/sim/random.h"
#include "hylo/sim/terrain.h"

namespace hylo::sim {

struct TrajectoryOptions {
  double cruise_speed_mps =
      1.2;  ///< speed on straight runs, m/s (0.5..1.5: a ground robot on gravel)
  double max_accel_mps2 = 0.3;           ///< longitudinal acceleration limit, m/s^2
  double max_lateral_accel_mps2 = 0.25;  ///< lateral acceleration limit in turns, m/s^2
  double min_turn_speed_mps = 0.5;       ///< turns are never slower than this, m/s
  double corner_cut_m = 3.0;             ///< a corner is rounded from this far before it, m
  double standstill_s =
      4.0;  ///< exact rest at the start, s (>= 3: the IMU start needs 1 s at rest)
  double knot_spacing_s = 0.1;     ///< B-spline knot spacing, s
  double imu_height_m = 0.6;       ///< IMU height above the wheel contacts, m
  double wheelbase_m = 1.0;        ///< front-rear wheel distance, m
  double track_m = 0.8;            ///< left-right wheel distance, m
  double jitter_z_m = 0.004;       ///< suspension jitter at cruise speed (1 sigma), m
  double jitter_tilt_rad = 0.004;  ///< roll/pitch jitter at cruise speed (1 sigma), rad

  bool IsValid(std::string* why) const;
};

/// Position, velocity, acceleration and attitude at one instant.
struct KinematicState {
  Eigen::Vector3d position_map = Eigen::Vector3d::Zero();  ///< IMU origin, m
  Eigen::Vector3d velocity_map = Eigen::Vector3d::Zero();  ///< m/s
  Eigen::Vector3d accel_map = Eigen::Vector3d::Zero();     ///< kinematic acceleration, m/s^2
  Eigen::Matrix3d R_map_imu = Eigen::Matrix3d::Identity();
  Eigen::Vector3d omega_imu = Eigen::Vector3d::Zero();  ///< body angular rate, rad/s
};

class Trajectory {
 public:
  /// Builds the trajectory along `waypoints_m` for `duration_ns` (after the route's end the
  /// vehicle stays at rest). Jitter draws from `rng`.
  static Trajectory FromRoute(const std::vector<Eigen::Vector2d>& waypoints_m,
                              const Terrain& terrain, const TrajectoryOptions& options,
                              int64_t duration_ns, Rng* rng);

  /// Full state at `t_ns` (since the session start, within [0, duration_ns]).
  KinematicState StateAt(int64_t t_ns) const;
  /// Pose only (cheaper): T_map_imu at `t_ns`.
  Eigen::Isometry3d PoseAt(int64_t t_ns) const;

  int64_t duration_ns() const { return duration_ns_; }
  double path_length_m() const { return path_length_m_; }  ///< distance driven, m
  double max_tilt_rad() const { return max_tilt_rad_; }    ///< max |roll|, |pitch| at knots

 private:
  using Knot = Eigen::Matrix<double, 6, 1>;  // x, y, z, yaw, pitch, roll
  void Evaluate(int64_t t_ns, Knot* value, Knot* d1, Knot* d2) const;

  std::vector<Knot> control_;
  double knot_s_ = 0.1;
  int64_t duration_ns_ = 0;
  double path_length_m_ = 0.0;
  double max_tilt_rad_ = 0.0;
};

/// R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d RotationFromYawPitchRoll(double yaw, double pitch, double roll);

}  // namespace hylo::sim
