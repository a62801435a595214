// A scenario's files and the configuration from its sensor sheet.
#include "hylo/sim_io/scenario_writer.h"

#include <filesystem>

#include "file_sink.h"
#include "hylo/io/atomic_file.h"
#include "hylo/io/trajectory_io.h"
#include "hylo/sim/scenario_simulator.h"
#include "hylo/sim_io/session_writer.h"
#include "json_parts.h"

namespace hylo::sim {
namespace {

io::Json ImuJson(const ImuGrade& imu) {
  io::Json j = io::Json::object();
  j["grade"] = imu.grade;
  j["label"] = imu.Label();
  j["rate_hz"] = imu.base.rate_hz;
  j["gravity_mps2"] = imu.base.gravity_mps2;
  j["accel_noise_density"] = imu.base.accel_noise_density;
  j["gyro_noise_density"] = imu.base.gyro_noise_density;
  j["accel_bias_random_walk"] = imu.base.accel_bias_random_walk;
  j["gyro_bias_random_walk"] = imu.base.gyro_bias_random_walk;
  j["accel_bias_initial_sigma"] = imu.base.accel_bias_initial_sigma;
  j["gyro_bias_initial_sigma"] = imu.base.gyro_bias_initial_sigma;
  j["accel_bias_instability_mps2"] = imu.accel_bias_instability_mps2;
  j["gyro_bias_instability_radps"] = imu.gyro_bias_instability_radps;
  j["bias_correlation_s"] = imu.bias_correlation_s;
  j["accel_scale_sigma"] = imu.accel_scale_sigma;
  j["gyro_scale_sigma"] = imu.gyro_scale_sigma;
  j["misalignment_sigma_rad"] = imu.misalignment_sigma_rad;
  return j;
}

io::Json SiteJson(const SiteRecipe& s) {
  io::Json j = io::Json::object();
  j["yard_size_m"] = io::Json::array({s.yard_size_m.x(), s.yard_size_m.y()});
  j["bay_m"] = io::Json::array({s.bay_m.x(), s.bay_m.y()});
  j["structure_density"] = s.structure_density;
  j["clutter_per_100m2"] = s.clutter_per_100m2;
  j["hills"] = s.hills;
  j["trenches"] = s.trenches;
  j["bumps"] = s.bumps;
  j["undulation_m"] = s.undulation_m;
  j["undulation_wavelength_m"] = s.undulation_wavelength_m;
  j["gravel_sigma_m"] = s.gravel_sigma_m;
  j["featureless_m"] = s.featureless_m;
  j["start_slope_deg"] = s.start_slope_deg;
  j["route_a_m"] = s.route_a_m;
  j["route_b_m"] = s.route_b_m;
  j["changed_fraction"] = s.changed_fraction;
  return j;
}

io::Json VibrationJson(const Vibration& v) {
  io::Json j = io::Json::object();
  for (const auto* tones : {&v.translation, &v.rotation}) {
    io::Json list = io::Json::array();
    for (const Vibration::Tone& t : *tones) {
      list.push_back({{"frequency_hz", t.frequency_hz}, {"amplitude", Vec(t.amplitude)}});
    }
    j[tones == &v.translation ? "translation_m" : "rotation_rad"] = list;
  }
  j["ramp_s"] = v.ramp_s;
  return j;
}

}  // namespace

config::RunConfig ScenarioRunConfig(const SensorSheet& sheet, const std::string& config_dir) {
  config::RunConfig config = config::LoadRunConfig(
      (std::filesystem::path(config_dir) / (sheet.preset + ".yaml")).string());
  config.T_imu_lidar.translation_m = sheet.translation_m;
  config.T_imu_lidar.rotation_rpy_deg = sheet.rotation_rpy_deg;
  estimation::ImuOptions& imu = config.pipeline.imu;
  imu.rate_hz = sheet.imu_rate_hz;
  imu.noise.gyro_noise_density = sheet.gyro_noise_density;
  imu.noise.accel_noise_density = sheet.accel_noise_density;
  imu.noise.gyro_bias_random_walk = sheet.gyro_bias_random_walk;
  imu.noise.accel_bias_random_walk = sheet.accel_bias_random_walk;
  // The sheet gives t_lidar - t_imu of one instant; the pipeline moves scans by t_imu - t_lidar.
  config.pipeline.lidar.time_offset_s = -sheet.lidar_time_offset_s;
  config.pipeline.output.dense_map_voxel_m = 0.0;
  std::string why;
  if (!config.IsValid(&why)) {
    throw config::ConfigError("scenario " + std::to_string(sheet.scenario) + " sheet on preset " +
                              sheet.preset + ": " + why);
  }
  return config;
}

io::Json ScenarioToJson(const Scenario& s) {
  io::Json j = io::Json::object();
  j["number"] = static_cast<unsigned long long>(s.number);
  j["summary"] = s.Summary();
  j["site"] = SiteJson(s.site);
  j["lidar"] = {{"kind", ToString(s.lidar.kind)},
                {"rate_hz", s.lidar.rate_hz},
                {"min_range_m", s.lidar.min_range_m},
                {"max_range_m", s.lidar.max_range_m},
                {"range_noise_m", s.lidar.range_noise_m},
                {"preset", s.lidar.preset},
                {"time_convention", s.lidar.time_convention}};
  j["T_imu_lidar"] = PoseJson(s.T_imu_lidar);
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.linear() = s.R_vehicle_imu;
  j["T_vehicle_imu"] = PoseJson(mount);
  j["lidar_time_offset_ns"] = static_cast<long long>(s.lidar_time_offset_ns);
  j["imu"] = ImuJson(s.imu);
  const TrajectoryOptions& t = s.trajectory;
  j["motion"] = {{"cruise_speed_mps", t.cruise_speed_mps},
                 {"max_accel_mps2", t.max_accel_mps2},
                 {"max_lateral_accel_mps2", t.max_lateral_accel_mps2},
                 {"jitter_z_m", t.jitter_z_m},
                 {"jitter_tilt_rad", t.jitter_tilt_rad},
                 {"standstill_s", t.standstill_s},
                 {"max_drive_a_s", s.max_drive_a_s},
                 {"max_drive_b_s", s.max_drive_b_s}};
  j["vibration"] = VibrationJson(s.vibration);
  return j;
}

SessionSummary WriteScenarioSession(const Scenario& scenario, const Site& site, SessionId session,
                                    const config::RunConfig& config, const std::string& dir,
                                    const std::function<void(std::size_t, std::size_t)>& progress,
                                    logs::LogFormat format) {
  std::filesystem::create_directories(dir);
  const ScenarioSimulator simulator(scenario, site, session);
  BagLayout layout;
  layout.imu_topic = config.imu.topic;
  layout.points_topic = config.lidar.topic;
  layout.point_layout = config.lidar.time_convention;
  layout.accel_units_mps2 = config.imu.accel_scale;
  FileSink sink(SessionLogPath(dir, session, format), layout, format);
  const SessionSummary summary = simulator.Run(&sink, progress);
  sink.Close();
  io::WriteTum(SessionTruthPath(dir, session), sink.truth());
  io::Json j = io::Json::object();
  j["generator"] = "hylo simulate --scenario " + std::to_string(scenario.number);
  j["session"] = ToString(session);
  j["role"] = session == SessionId::kA ? "mapping (from outside the fence, the spur if any)"
                                       : "localization (over the yard's lanes)";
  j["frames"] = "map (site), imu (body), lidar; T_a_b maps points from b to a";
  j["topics"] = {{"imu", layout.imu_topic},
                 {"points", layout.points_topic},
                 {"point_time_convention", logs::ToString(layout.point_layout)},
                 {"accel_units_mps2", layout.accel_units_mps2}};
  j["start_t_ns"] = static_cast<long long>(simulator.start_ns());
  j["duration_s"] = summary.duration_s;
  j["counts"] = {
      {"imu_samples", summary.imu_samples}, {"scans", summary.scans}, {"points", summary.points}};
  j["path_length_m"] = summary.path_length_m;
  j["max_tilt_deg"] = summary.max_tilt_deg;
  j["imu_initial_accel_bias_mps2"] = Vec(summary.initial_accel_bias);
  j["imu_initial_gyro_bias_radps"] = Vec(summary.initial_gyro_bias);
  j["scenario"] = ScenarioToJson(scenario);
  io::WriteJsonFile(SessionManifestPath(dir, session), j);
  return summary;
}

void WriteScenarioSheet(const SensorSheet& sheet, const config::RunConfig& config,
                        const std::string& dir) {
  std::filesystem::create_directories(dir);
  io::WriteFileAtomically((std::filesystem::path(dir) / "sensor_sheet.yaml").string(),
                          sheet.ToYaml());
  config::SaveRunConfig((std::filesystem::path(dir) / "config.yaml").string(), config);
}

}  // namespace hylo::sim
