#include "hylo/config/run_config.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <utility>

#include "hylo/registration/pose_guess.h"
#include "run_config_fields.h"
#include "yaml_visitors.h"

namespace hylo::config {
namespace {

// Writes "<field> = <value>: <constraint>" into *why and returns false.
template <class T>
bool Invalid(std::string* why, const std::string& field, const T& value,
             const std::string& constraint) {
  if (why != nullptr) {
    std::ostringstream os;
    os << field << " = " << value << ": " << constraint;
    *why = os.str();
  }
  return false;
}

bool PositiveFinite(double value) { return std::isfinite(value) && value > 0.0; }

// Runs a section's IsValid and prefixes its message with the section name.
template <class S>
bool SectionValid(const S& section, const std::string& name, std::string* why) {
  std::string inner;
  if (section.IsValid(&inner)) return true;
  if (why != nullptr) *why = name + "." + inner;
  return false;
}

}  // namespace

bool LidarConfig::IsValid(std::string* why) const {
  if (topic.empty()) return Invalid(why, "topic", "''", "must name a PointCloud2 topic");
  if (!std::isfinite(min_range_m) || min_range_m < 0.0)
    return Invalid(why, "min_range_m", min_range_m, "must be finite and >= 0");
  if (!std::isfinite(max_range_m) || max_range_m <= min_range_m)
    return Invalid(why, "max_range_m", max_range_m, "must be finite and > min_range_m");
  if (!PositiveFinite(scan_period_s) || scan_period_s > 1.0)
    return Invalid(why, "scan_period_s", scan_period_s, "must be in (0, 1] s");
  return true;
}

bool ImuConfig::IsValid(std::string* why) const {
  if (!enabled) return true;
  if (topic.empty()) return Invalid(why, "topic", "''", "must name an Imu topic (or imu: none)");
  if (!PositiveFinite(rate_hz)) return Invalid(why, "rate_hz", rate_hz, "must be > 0");
  if (!std::isfinite(gravity_mps2) || gravity_mps2 < 9.7 || gravity_mps2 > 9.9)
    return Invalid(why, "gravity_mps2", gravity_mps2, "must be within [9.7, 9.9] m/s^2 on Earth");
  if (accel_scale != 1.0 && std::abs(accel_scale - gravity_mps2) > 0.2)
    return Invalid(why, "accel_scale", accel_scale,
                   "must be 1 (driver reports m/s^2) or about gravity_mps2 (driver reports g)");
  return SectionValid(noise, "noise", why);
}

Eigen::Isometry3d TransformConfig::ToIsometry() const {
  const Eigen::Vector3d rpy = rotation_rpy_deg * (M_PI / 180.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = translation_m;
  return T;
}

bool TransformConfig::IsValid(std::string* why) const {
  if (!translation_m.allFinite())
    return Invalid(why, "translation_m", translation_m.transpose(), "must be finite");
  if (!rotation_rpy_deg.allFinite() || rotation_rpy_deg.cwiseAbs().maxCoeff() > 360.0)
    return Invalid(why, "rotation_rpy_deg", rotation_rpy_deg.transpose(),
                   "must be finite and within [-360, 360] degrees");
  return true;
}

bool RunConfig::IsValid(std::string* why) const {
  if (backend != "ieskf" && backend != "sliding_window")
    return Invalid(why, "backend", backend, "must be ieskf or sliding_window");
  return SectionValid(lidar, "lidar", why) && SectionValid(imu, "imu", why) &&
         SectionValid(T_imu_lidar, "T_imu_lidar", why) &&
         SectionValid(preprocess, "preprocess", why) && SectionValid(init, "init", why) &&
         SectionValid(ieskf, "ieskf", why) &&
         SectionValid(sliding_window, "sliding_window", why) &&
         SectionValid(planes, "planes", why) &&
         SectionValid(map, "map", why) && SectionValid(localization, "localization", why) &&
         SectionValid(output, "output", why) && SectionValid(ground, "ground", why);
}

bool MapConfig::IsValid(std::string* why) const {
  if (!mapping::MapManagerOptions::IsValid(why)) return false;
  if (!std::isfinite(prior_resolution_m) || prior_resolution_m < 0.0)
    return Invalid(why, "prior_resolution_m", prior_resolution_m, "must be finite and >= 0");
  if (!std::isfinite(update_after_s) || (update_after_s < 0.0 && update_after_s != -1.0))
    return Invalid(why, "update_after_s", update_after_s, "must be -1 (never) or >= 0 s");
  return true;
}

bool LocalizationConfig::IsValid(std::string* why) const {
  if (!initial_guess.empty()) {
    try {
      registration::ParsePoseGuess(initial_guess);
    } catch (const std::invalid_argument& e) {
      return Invalid(why, "initial_guess", "'" + initial_guess + "'", e.what());
    }
  }
  estimation::LocalizationOptions checked = options;
  checked.update_after_s = -1.0;  // validated in map:
  return checked.IsValid(why);
}

bool OutputConfig::IsValid(std::string* why) const {
  if (!std::isfinite(dense_map_voxel_m) || dense_map_voxel_m < 0.0)
    return Invalid(why, "dense_map_voxel_m", dense_map_voxel_m, "must be finite and >= 0 (0 = off)");
  if (dense_map_voxel_m > 0.0 && dense_map_voxel_m < 0.01)
    return Invalid(why, "dense_map_voxel_m", dense_map_voxel_m,
                   "must be >= 0.01 m (finer voxels keep every return and exhaust memory)");
  const std::pair<const char*, const std::string*> frames[] = {
      {"map_frame", &map_frame}, {"odom_frame", &odom_frame}, {"base_frame", &base_frame}};
  for (const auto& [key, name] : frames) {
    if (name->empty() || name->front() == '/' || name->find_first_of(" \t") != std::string::npos)
      return Invalid(why, key, "'" + *name + "'",
                     "must be a non-empty frame name without spaces or a leading '/'");
  }
  if (map_frame == odom_frame || odom_frame == base_frame || map_frame == base_frame)
    return Invalid(why, "odom_frame", "'" + odom_frame + "'",
                   "map, odom and base frames must differ");
  return true;
}

estimation::OdometryPipelineOptions RunConfig::PipelineOptions() const {
  estimation::OdometryPipelineOptions o;
  if (!estimation::ParseBackend(backend, &o.estimator.backend)) {
    throw ConfigError("backend = " + backend + ": unknown estimator back-end");
  }
  o.estimator.use_imu = imu.enabled;
  o.estimator.imu_noise = imu.noise;
  o.estimator.ieskf = ieskf;
  o.estimator.sliding_window = sliding_window;
  o.gravity_mps2 = imu.gravity_mps2;
  o.init = init;
  // A gap is five missing samples at the nominal rate.
  o.queue.imu_gap_ns = static_cast<int64_t>(std::llround(5e9 / imu.rate_hz));
  o.preprocess = preprocess;
  o.preprocess.min_range_m = lidar.min_range_m;
  o.preprocess.max_range_m = lidar.max_range_m;
  o.planes = planes;
  o.map = map;
  o.localization = localization.options;
  o.localization.update_after_s = map.update_after_s;
  o.registered_scan_voxel_m = output.dense_map_voxel_m;
  const Eigen::Isometry3d T = T_imu_lidar.ToIsometry();
  o.T_imu_lidar = estimation::lie::SE3d(estimation::lie::SO3d::FromMatrix(T.linear()),
                                        T.translation());
  return o;
}

io::LogReadOptions RunConfig::LogOptions() const {
  io::LogReadOptions options;
  options.lidar_topic = lidar.topic;
  options.imu_topic = imu.enabled ? imu.topic : std::string();
  options.time_convention = lidar.time_convention;
  options.imu_accel_scale = imu.accel_scale;
  return options;
}

RunConfig ParseRunConfig(const std::string& yaml_text, const std::string& source_name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source_name + ": malformed YAML: " + e.what());
  }
  RunConfig config;
  if (root.IsNull()) return config;  // an empty file keeps every default
  if (!root.IsMap()) throw ConfigError(source_name + ": expected a map of keys at the top level");
  YamlReadVisitor reader(root, "", source_name);
  VisitFields(reader, config);
  reader.RejectUnknownKeys();
  std::string why;
  if (!config.IsValid(&why)) throw ConfigError(source_name + ": invalid value: " + why);
  return config;
}

RunConfig LoadRunConfig(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw ConfigError("cannot read configuration file '" + path + "'");
  std::ostringstream text;
  text << file.rdbuf();
  return ParseRunConfig(text.str(), path);
}

std::string ToYaml(const RunConfig& config) {
  YAML::Emitter out;
  out.SetDoublePrecision(10);
  out << YAML::BeginMap;
  RunConfig copy = config;  // the visitor takes fields by non-const reference
  YamlWriteVisitor writer(&out);
  VisitFields(writer, copy);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void SaveRunConfig(const std::string& path, const RunConfig& config) {
  std::ofstream file(path);
  if (!file) throw ConfigError("cannot write configuration file '" + path + "'");
  file << "# effective configuration written by hylo\n" << ToYaml(config);
  if (!file) throw ConfigError("failed while writing configuration file '" + path + "'");
}

}  // namespace hylo::config
