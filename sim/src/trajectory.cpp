// Ground-truth trajectory: knot values from the route and the terrain, uniform cubic
// B-spline evaluation with analytic derivatives (de Boor; matrix form as in Qin 2000,
// "General matrix representations for B-splines").
#include "hylo/sim/trajectory.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "hylo/common/check.h"
#include "hylo/common/time.h"
#include "route.h"

namespace hylo::sim {

bool TrajectoryOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(cruise_speed_mps > 0.0))
    os << "cruise_speed_mps = " << cruise_speed_mps << " must be > 0";
  else if (!(max_accel_mps2 > 0.0))
    os << "max_accel_mps2 = " << max_accel_mps2 << " must be > 0";
  else if (!(max_lateral_accel_mps2 > 0.0))
    os << "max_lateral_accel_mps2 = " << max_lateral_accel_mps2 << " must be > 0";
  else if (!(min_turn_speed_mps > 0.0 && min_turn_speed_mps <= cruise_speed_mps))
    os << "min_turn_speed_mps = " << min_turn_speed_mps << " must be in (0, cruise_speed_mps]";
  else if (!(corner_cut_m >= 0.0))
    os << "corner_cut_m = " << corner_cut_m << " must be >= 0";
  else if (!(standstill_s >= 0.0))
    os << "standstill_s = " << standstill_s << " must be >= 0";
  else if (!(knot_spacing_s > 0.0))
    os << "knot_spacing_s = " << knot_spacing_s << " must be > 0";
  else if (!(wheelbase_m > 0.0 && track_m > 0.0))
    os << "wheelbase_m and track_m must be > 0";
  else if (!(jitter_z_m >= 0.0 && jitter_tilt_rad >= 0.0))
    os << "jitter values must be >= 0";
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

Eigen::Matrix3d RotationFromYawPitchRoll(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Trajectory Trajectory::FromRoute(const std::vector<Eigen::Vector2d>& waypoints_m,
                                 const Terrain& terrain, const TrajectoryOptions& options,
                                 int64_t duration_ns, Rng* rng) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("TrajectoryOptions: " + why);
  HYLO_CHECK(duration_ns > 0, "duration must be positive");
  const RoutePlan plan(waypoints_m, options);
  Trajectory traj;
  traj.knot_s_ = options.knot_spacing_s;
  traj.duration_ns_ = duration_ns;
  // Motion starts two knots after the standstill so that every spline segment overlapping
  // [0, standstill_s] has identical control points (exact rest).
  const double t_move = options.standstill_s + 2.0 * options.knot_spacing_s;
  const int count = static_cast<int>(std::ceil(NanosToSeconds(duration_ns) / traj.knot_s_)) + 4;
  double previous_yaw = 0.0;
  for (int j = 0; j < count; ++j) {
    const double tau = (j - 1) * traj.knot_s_;  // control j sits at time (j - 1) * spacing
    Eigen::Vector2d xy;
    double heading = 0.0, speed = 0.0, distance = 0.0;
    plan.Sample(tau - t_move, &xy, &heading, &speed, &distance);
    const double yaw =
        j == 0 ? heading : previous_yaw + std::remainder(heading - previous_yaw, 2 * M_PI);
    previous_yaw = yaw;
    const Eigen::Vector2d fwd(std::cos(yaw), std::sin(yaw)), left(-fwd.y(), fwd.x());
    const auto h = [&](double f, double l) {
      const Eigen::Vector2d p = xy + f * fwd + l * left;
      return terrain.BaseHeight(p.x(), p.y());
    };
    const double hl = 0.5 * options.wheelbase_m, hw = 0.5 * options.track_m;
    const double fl = h(hl, hw), fr = h(hl, -hw), rl = h(-hl, hw), rr = h(-hl, -hw);
    // Nose up is a negative pitch in the ZYX convention (body x gains +z).
    double pitch = -std::atan2(0.5 * (fl + fr - rl - rr), options.wheelbase_m);
    double roll = std::atan2(0.5 * (fl + rl - fr - rr), options.track_m);
    double z = 0.25 * (fl + fr + rl + rr) + options.imu_height_m;
    const double shake = std::min(1.0, speed / options.cruise_speed_mps);
    if (shake > 0.0) {
      z += shake * rng->Gaussian(options.jitter_z_m);
      pitch += shake * rng->Gaussian(options.jitter_tilt_rad);
      roll += shake * rng->Gaussian(options.jitter_tilt_rad);
    }
    Knot knot;
    knot << xy.x(), xy.y(), z, yaw, pitch, roll;
    traj.control_.push_back(knot);
    traj.path_length_m_ = distance;
    traj.max_tilt_rad_ = std::max({traj.max_tilt_rad_, std::abs(pitch), std::abs(roll)});
  }
  return traj;
}

void Trajectory::Evaluate(int64_t t_ns, Knot* value, Knot* d1, Knot* d2) const {
  const double t = NanosToSeconds(std::clamp<int64_t>(t_ns, 0, duration_ns_)) / knot_s_;
  const int k =
      std::clamp(static_cast<int>(std::floor(t)), 0, static_cast<int>(control_.size()) - 4);
  const double u = t - k, u2 = u * u, u3 = u2 * u, w = 1.0 - u;
  const Knot& c0 = control_[k];
  const Knot& c1 = control_[k + 1];
  const Knot& c2 = control_[k + 2];
  const Knot& c3 = control_[k + 3];
  *value = (w * w * w * c0 + (3 * u3 - 6 * u2 + 4) * c1 + (-3 * u3 + 3 * u2 + 3 * u + 1) * c2 +
            u3 * c3) /
           6.0;
  if (d1 != nullptr) {
    *d1 =
        (-0.5 * w * w * c0 + (1.5 * u2 - 2 * u) * c1 + (-1.5 * u2 + u + 0.5) * c2 + 0.5 * u2 * c3) /
        knot_s_;
  }
  if (d2 != nullptr) {
    *d2 = (w * c0 + (3 * u - 2) * c1 + (1 - 3 * u) * c2 + u * c3) / (knot_s_ * knot_s_);
  }
}

KinematicState Trajectory::StateAt(int64_t t_ns) const {
  Knot v, d1, d2;
  Evaluate(t_ns, &v, &d1, &d2);
  KinematicState s;
  s.position_map = v.head<3>();
  s.velocity_map = d1.head<3>();
  s.accel_map = d2.head<3>();
  const double yaw = v[3], pitch = v[4], roll = v[5];
  s.R_map_imu = RotationFromYawPitchRoll(yaw, pitch, roll);
  const double dyaw = d1[3], dpitch = d1[4], droll = d1[5];
  // Body rates from ZYX Euler rates: R^T dR/dt = [omega]x.
  s.omega_imu << droll - dyaw * std::sin(pitch),
      dpitch * std::cos(roll) + dyaw * std::sin(roll) * std::cos(pitch),
      -dpitch * std::sin(roll) + dyaw * std::cos(roll) * std::cos(pitch);
  return s;
}

Eigen::Isometry3d Trajectory::PoseAt(int64_t t_ns) const {
  Knot v;
  Evaluate(t_ns, &v, nullptr, nullptr);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = RotationFromYawPitchRoll(v[3], v[4], v[5]);
  T.translation() = v.head<3>();
  return T;
}

}  // namespace hylo::sim
