// Spinning lidar: beam tables, options and the per-laser ray casting of one scan.
#include "hylo/sim/lidar_model.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "hylo/common/check.h"
#include "hylo/sim/random.h"

namespace hylo::sim {
namespace {

// The pose dt seconds after `state` to second order (constant acceleration, constant body
// rate). Lasers of one column fire within 45 us of the column start, so the error is below
// 1e-8 m and 1e-8 rad: far under the float32 resolution of the stored points, at a 16th of
// the cost of evaluating the spline per laser.
Eigen::Isometry3d ExtrapolatePose(const KinematicState& state, double dt) {
  const Eigen::Vector3d phi = state.omega_imu * dt;
  Eigen::Matrix3d phi_x;
  phi_x << 0, -phi.z(), phi.y(), phi.z(), 0, -phi.x(), -phi.y(), phi.x(), 0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = state.R_map_imu * (Eigen::Matrix3d::Identity() + phi_x + 0.5 * phi_x * phi_x);
  T.translation() = state.position_map + state.velocity_map * dt + 0.5 * state.accel_map * dt * dt;
  return T;
}

}  // namespace

std::string ToString(LidarModel model) { return model == LidarModel::kVlp16 ? "vlp16" : "rs16"; }

bool ParseLidarModel(const std::string& name, LidarModel* model) {
  if (name == "vlp16")
    *model = LidarModel::kVlp16;
  else if (name == "rs16")
    *model = LidarModel::kRs16;
  else
    return false;
  return true;
}

BeamTable MakeBeamTable(LidarModel model) {
  BeamTable table;
  if (model == LidarModel::kVlp16) {
    table.elevation_deg = {-15, 1, -13, 3, -11, 5, -9, 7, -7, 9, -5, 11, -3, 13, -1, 15};
    table.slot_ns = 2304;
  } else {
    table.elevation_deg = {-15, -13, -11, -9, -7, -5, -3, -1, 15, 13, 11, 9, 7, 5, 3, 1};
    table.slot_ns = 3000;
  }
  for (int i = 0; i < 16; ++i) {
    table.ring[i] =
        static_cast<uint16_t>(std::count_if(table.elevation_deg.begin(), table.elevation_deg.end(),
                                            [&](double e) { return e < table.elevation_deg[i]; }));
  }
  return table;
}

Eigen::Isometry3d LidarOptions::DefaultExtrinsic() {
  // Lidar 0.35 m above and 0.1 m ahead of the IMU, mounted with a small tilt and yaw.
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = RotationFromYawPitchRoll(3.0 * M_PI / 180, -2.0 * M_PI / 180, 1.0 * M_PI / 180);
  T.translation() = Eigen::Vector3d(0.10, -0.02, 0.35);
  return T;
}

int64_t LidarOptions::period_ns() const { return std::llround(1e9 / rate_hz); }
int LidarOptions::columns() const { return static_cast<int>(std::lround(360.0 / column_deg)); }

bool LidarOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  const int64_t column_ns = rate_hz > 0 && column_deg > 0 ? period_ns() / columns() : 0;
  if (!(rate_hz > 0.0 && rate_hz <= 50.0))
    os << "rate_hz = " << rate_hz << " must be in (0, 50]";
  else if (!(column_deg > 0.0 && column_deg <= 45.0))
    os << "column_deg = " << column_deg << " must be in (0, 45]";
  else if (column_ns < 16 * MakeBeamTable(model).slot_ns)
    os << "column_deg = " << column_deg << " at rate_hz = " << rate_hz
       << " leaves less time per column than one firing sequence";
  else if (!(min_range_m >= 0.0 && max_range_m > min_range_m))
    os << "need 0 <= min_range_m (" << min_range_m << ") < max_range_m (" << max_range_m << ")";
  else if (!(range_noise_m >= 0.0))
    os << "range_noise_m = " << range_noise_m << " must be >= 0";
  else if (!(dropout_probability >= 0.0 && dropout_probability < 1.0))
    os << "dropout_probability = " << dropout_probability << " must be in [0, 1)";
  else if (!(min_incidence_cos >= 0.0 && min_incidence_cos < 1.0))
    os << "min_incidence_cos = " << min_incidence_cos << " must be in [0, 1)";
  else if (!(intensity_noise >= 0.0))
    os << "intensity_noise = " << intensity_noise << " < 0";
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

LidarSimulator::LidarSimulator(const LidarOptions& options, const World& world,
                               const Trajectory& trajectory, uint64_t seed)
    : options_(options),
      beams_(MakeBeamTable(options.model)),
      world_(world),
      trajectory_(trajectory),
      seed_(seed) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("LidarOptions: " + why);
  for (int i = 0; i < 16; ++i) {
    const double e = beams_.elevation_deg[i] * M_PI / 180.0;
    elevation_cos_sin_[i] = Eigen::Vector2d(std::cos(e), std::sin(e));
  }
}

LidarScan LidarSimulator::Scan(int index, int64_t session_start_ns,
                               std::vector<ReturnTruth>* truth) const {
  const int64_t period = period_ns();
  const int columns = options_.columns();
  const int64_t scan_start = static_cast<int64_t>(index) * period;  // since session start
  Rng rng = Rng::Derive(seed_, 0x11da5, static_cast<uint64_t>(index));
  LidarScan scan;
  scan.t_ns = session_start_ns + scan_start + options_.time_offset_ns;
  scan.frame_id = "lidar";
  scan.points.reserve(static_cast<size_t>(columns) * 12);
  if (truth != nullptr) truth->clear();
  const double azimuth0 = options_.start_azimuth_deg * M_PI / 180.0;
  // The head turns clockwise seen from above (as Velodyne and RoboSense heads do): slot s of
  // a column fires s * slot_ns later, at an azimuth smaller by the matching angle.
  std::array<Eigen::Vector2d, 16> slot_turn;
  for (int slot = 0; slot < 16; ++slot) {
    const double angle = -2.0 * M_PI * double(slot * beams_.slot_ns) / double(period);
    slot_turn[slot] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
  for (int c = 0; c < columns; ++c) {
    const int64_t column_offset = c * period / columns;
    const double column_azimuth = azimuth0 - 2.0 * M_PI * double(column_offset) / double(period);
    const double ca = std::cos(column_azimuth), sa = std::sin(column_azimuth);
    const KinematicState state = trajectory_.StateAt(scan_start + column_offset);
    for (int slot = 0; slot < 16; ++slot) {
      const int64_t offset = column_offset + slot * beams_.slot_ns;
      const Eigen::Vector2d& turn = slot_turn[slot];
      const double cos_az = ca * turn.x() - sa * turn.y(), sin_az = sa * turn.x() + ca * turn.y();
      const Eigen::Vector2d& cs = elevation_cos_sin_[slot];
      const Eigen::Vector3d dir_lidar(cs.x() * cos_az, cs.x() * sin_az, cs.y());
      const Eigen::Isometry3d T_map_lidar =
          ExtrapolatePose(state, 1e-9 * double(slot * beams_.slot_ns)) * options_.T_imu_lidar;
      Ray ray;
      ray.origin = T_map_lidar.translation();
      ray.direction = T_map_lidar.linear() * dir_lidar;
      RayHit hit;
      const bool returned = world_.Raycast(ray, options_.max_range_m, &hit);
      // Draw every random number for every laser so one return's fate never shifts the
      // noise of the others (stable streams when options change slightly).
      const double u_drop = rng.Uniform(), n_range = rng.Gaussian(), n_int = rng.Gaussian();
      if (!returned || u_drop < options_.dropout_probability) continue;
      const double cos_incidence = std::abs(hit.normal_map.dot(ray.direction));
      if (cos_incidence < options_.min_incidence_cos) continue;
      const double range = hit.range_m + options_.range_noise_m * n_range;
      if (range < options_.min_range_m || range > options_.max_range_m) continue;
      ScanPoint point;
      point.position_lidar = (range * dir_lidar).cast<float>();
      const double intensity =
          255.0 * hit.reflectivity * (0.2 + 0.8 * cos_incidence) + options_.intensity_noise * n_int;
      point.intensity = static_cast<float>(std::round(std::clamp(intensity, 0.0, 255.0)));
      point.offset_ns = static_cast<int32_t>(offset);
      point.ring = beams_.ring[slot];
      scan.points.push_back(point);
      if (truth != nullptr) truth->push_back({hit.point_map, hit.range_m, hit.primitive});
    }
  }
  scan.end_t_ns = scan.points.empty() ? scan.t_ns : scan.t_ns + scan.points.back().offset_ns;
  return scan;
}

}  // namespace hylo::sim
