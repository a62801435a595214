// SimulationOptions as JSON, so every manifest records every parameter.
#include "hylo/sim_io/session_writer.h"

namespace hylo::sim {
namespace {
io::Json Vec2(const Eigen::Vector2d& v) { return io::Json::array({v.x(), v.y()}); }
}  // namespace

io::Json OptionsToJson(const SimulationOptions& o) {
  io::Json j = io::Json::object();
  j["seed"] = static_cast<unsigned long long>(o.seed);
  j["duration_a_s"] = o.duration_a_s;
  j["duration_b_s"] = o.duration_b_s;
  j["start_a_ns"] = static_cast<long long>(o.start_a_ns);
  j["start_b_ns"] = static_cast<long long>(o.start_b_ns);
  j["index_cell_m"] = o.index_cell_m;
  io::Json& t = j["terrain"];
  t["min_m"] = Vec2(o.terrain.min_m);
  t["max_m"] = Vec2(o.terrain.max_m);
  t["resolution_m"] = o.terrain.resolution_m;
  t["gravel_sigma_m"] = o.terrain.gravel_sigma_m;
  t["reflectivity"] = o.terrain.reflectivity;
  io::Json& v = j["trajectory"];
  v["cruise_speed_mps"] = o.trajectory.cruise_speed_mps;
  v["max_accel_mps2"] = o.trajectory.max_accel_mps2;
  v["max_lateral_accel_mps2"] = o.trajectory.max_lateral_accel_mps2;
  v["min_turn_speed_mps"] = o.trajectory.min_turn_speed_mps;
  v["corner_cut_m"] = o.trajectory.corner_cut_m;
  v["standstill_s"] = o.trajectory.standstill_s;
  v["knot_spacing_s"] = o.trajectory.knot_spacing_s;
  v["imu_height_m"] = o.trajectory.imu_height_m;
  v["wheelbase_m"] = o.trajectory.wheelbase_m;
  v["track_m"] = o.trajectory.track_m;
  v["jitter_z_m"] = o.trajectory.jitter_z_m;
  v["jitter_tilt_rad"] = o.trajectory.jitter_tilt_rad;
  io::Json& l = j["lidar"];
  l["model"] = ToString(o.lidar.model);
  const BeamTable beams = MakeBeamTable(o.lidar.model);
  l["elevation_deg_by_slot"] = io::Json(beams.elevation_deg);
  l["slot_ns"] = static_cast<long long>(beams.slot_ns);
  l["rate_hz"] = o.lidar.rate_hz;
  l["column_deg"] = o.lidar.column_deg;
  l["min_range_m"] = o.lidar.min_range_m;
  l["max_range_m"] = o.lidar.max_range_m;
  l["range_noise_m"] = o.lidar.range_noise_m;
  l["dropout_probability"] = o.lidar.dropout_probability;
  l["min_incidence_cos"] = o.lidar.min_incidence_cos;
  l["intensity_noise"] = o.lidar.intensity_noise;
  l["start_azimuth_deg"] = o.lidar.start_azimuth_deg;
  l["time_offset_ns"] = static_cast<long long>(o.lidar.time_offset_ns);
  io::Json& i = j["imu"];
  i["rate_hz"] = o.imu.rate_hz;
  i["gravity_mps2"] = o.imu.gravity_mps2;
  i["accel_noise_density"] = o.imu.accel_noise_density;
  i["gyro_noise_density"] = o.imu.gyro_noise_density;
  i["accel_bias_random_walk"] = o.imu.accel_bias_random_walk;
  i["gyro_bias_random_walk"] = o.imu.gyro_bias_random_walk;
  i["accel_bias_initial_sigma"] = o.imu.accel_bias_initial_sigma;
  i["gyro_bias_initial_sigma"] = o.imu.gyro_bias_initial_sigma;
  return j;
}

}  // namespace hylo::sim
