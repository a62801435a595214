// Ray casting a scan pattern from the moving lidar: the IMU's exact state every 100 us of the
// frame, carried to each shot at constant body rate and acceleration (< 1e-9 m over 100 us
// for the vibration's ~250 m/s^3 of jerk), then the lidar's mounting.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "hylo/lie/so3.h"
#include "hylo/sim/random.h"
#include "hylo/sim/scenario_simulator.h"

namespace hylo::sim {
namespace {

constexpr int64_t kStateStepNs = 100'000;

Eigen::Isometry3d Carried(const KinematicState& state, double dt_s) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = dt_s == 0.0 ? state.R_map_imu
                           : state.R_map_imu * lie::SO3d::Exp(state.omega_imu * dt_s).Matrix();
  T.translation() =
      state.position_map + state.velocity_map * dt_s + 0.5 * state.accel_map * dt_s * dt_s;
  return T;
}

}  // namespace

PatternLidar::PatternLidar(const SensorSpec& spec, const World& world, const VehicleMotion& motion,
                           const Eigen::Isometry3d& T_imu_lidar, int64_t time_offset_ns,
                           uint64_t seed)
    : spec_(spec),
      pattern_(spec.kind),
      world_(world),
      motion_(motion),
      T_imu_lidar_(T_imu_lidar),
      time_offset_ns_(time_offset_ns),
      seed_(seed) {
  if (!(spec.min_range_m >= 0.0 && spec.max_range_m > spec.min_range_m &&
        spec.range_noise_m >= 0.0 && spec.dropout_probability >= 0.0 &&
        spec.dropout_probability < 1.0)) {
    throw std::invalid_argument("SensorSpec of " + ToString(spec.kind) + ": invalid ranges/noise");
  }
}

LidarScan PatternLidar::Scan(int64_t index, int64_t session_start_ns) const {
  std::vector<Shot> shots;
  pattern_.Frame(index, &shots);
  const int64_t scan_start = index * period_ns();
  Rng rng = Rng::Derive(seed_, 0x11da5, static_cast<uint64_t>(index));
  LidarScan scan;
  scan.t_ns = session_start_ns + scan_start + time_offset_ns_;
  scan.frame_id = "lidar";
  scan.points.reserve(shots.size());
  KinematicState state;
  int64_t state_offset = -kStateStepNs;
  for (const Shot& shot : shots) {
    if (shot.offset_ns - state_offset >= kStateStepNs) {
      state = motion_.StateAt(scan_start + shot.offset_ns);
      state_offset = shot.offset_ns;
    }
    const Eigen::Isometry3d T_map_lidar =
        Carried(state, 1e-9 * double(shot.offset_ns - state_offset)) * T_imu_lidar_;
    Ray ray;
    ray.origin = T_map_lidar.translation();
    ray.direction = T_map_lidar.linear() * shot.direction_lidar;
    RayHit hit;
    const bool returned = world_.Raycast(ray, spec_.max_range_m, &hit);
    // Every shot draws its numbers, so one return's fate never shifts the others' noise.
    const double u_drop = rng.Uniform(), n_range = rng.Gaussian(), n_int = rng.Gaussian();
    if (!returned || u_drop < spec_.dropout_probability) continue;
    const double cos_incidence = std::abs(hit.normal_map.dot(ray.direction));
    if (cos_incidence < spec_.min_incidence_cos) continue;
    const double range = hit.range_m + spec_.range_noise_m * n_range;
    if (range < spec_.min_range_m || range > spec_.max_range_m) continue;
    ScanPoint point;
    point.position_lidar = (range * shot.direction_lidar).cast<float>();
    const double intensity = 255.0 * hit.reflectivity * (0.2 + 0.8 * cos_incidence) + 2.0 * n_int;
    point.intensity = static_cast<float>(std::round(std::clamp(intensity, 0.0, 255.0)));
    point.offset_ns = static_cast<int32_t>(shot.offset_ns);
    point.ring = shot.ring;
    scan.points.push_back(point);
  }
  scan.end_t_ns = scan.points.empty() ? scan.t_ns : scan.t_ns + scan.points.back().offset_ns;
  return scan;
}

}  // namespace hylo::sim
