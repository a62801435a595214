#include "hylo/config/run_config.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <utility>

#include "hylo/common/option_checks.h"
#include "hylo/io/atomic_file.h"
#include "hylo/localization/pose_guess.h"
#include "duplicate_keys.h"
#include "run_config_fields.h"
#include "yaml_visitors.h"

namespace hylo::config {

bool LidarStream::IsValid(std::string* why) const {
  return !topic.empty() || FailOption("topic", "''", "must name a PointCloud2 topic", why);
}

bool ImuStream::IsValid(double gravity_mps2, std::string* why) const {
  if (topic.empty()) return FailOption("topic", "''", "must name an Imu topic (or imu: none)", why);
  if (accel_scale != 1.0 && !(std::abs(accel_scale - gravity_mps2) <= 0.2)) {
    return FailOption("accel_scale", accel_scale,
                      "must be 1 (driver reports m/s^2) or about gravity_mps2 (driver reports g)",
                      why);
  }
  return true;
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
  if (!translation_m.allFinite()) {
    return FailOption("translation_m", translation_m.transpose(), "must be finite", why);
  }
  if (!rotation_rpy_deg.allFinite() || rotation_rpy_deg.cwiseAbs().maxCoeff() > 360.0) {
    return FailOption("rotation_rpy_deg", rotation_rpy_deg.transpose(),
                      "must be finite and within [-360, 360] degrees", why);
  }
  return true;
}

bool OutputFrames::IsValid(std::string* why) const {
  const std::pair<const char*, const std::string*> frames[] = {
      {"map_frame", &map_frame}, {"odom_frame", &odom_frame}, {"base_frame", &base_frame}};
  for (const auto& [key, name] : frames) {
    if (name->empty() || name->front() == '/' || name->find_first_of(" \t") != std::string::npos)
      return FailOption(key, "'" + *name + "'",
                        "must be a non-empty frame name without spaces or a leading '/'", why);
  }
  if (map_frame == odom_frame || odom_frame == base_frame || map_frame == base_frame)
    return FailOption("odom_frame", "'" + odom_frame + "'", "map, odom and base frames must differ",
                      why);
  return true;
}

RunConfig::RunConfig() { pipeline.output.dense_map_voxel_m = 0.1; }

bool RunConfig::IsValid(std::string* why) const {
  // The pipeline names its own fields by their YAML paths; the app-level pieces are checked
  // under the section they share with it.
  if (!pipeline.IsValid(why)) return false;
  if (!CheckSection(lidar, "lidar", why)) return false;
  if (pipeline.imu.enabled) {
    std::string inner;
    if (!imu.IsValid(pipeline.imu.gravity_mps2, &inner)) {
      if (why != nullptr) *why = "imu." + inner;
      return false;
    }
  }
  if (!CheckSection(T_imu_lidar, "T_imu_lidar", why) ||
      !CheckSection(prior_map, "prior_map", why) || !CheckSection(output, "output", why) ||
      !CheckSection(ground, "ground", why) || !CheckSection(inspection, "inspection", why)) {
    return false;
  }
  if (!initial_guess.empty()) {
    try {
      localization::ParsePoseGuess(initial_guess);
    } catch (const std::invalid_argument& e) {
      return FailOption("localization.initial_guess", "'" + initial_guess + "'", e.what(), why);
    }
  }
  return true;
}

odometry::OdometryPipelineOptions RunConfig::PipelineOptions() const {
  odometry::OdometryPipelineOptions o = pipeline;
  const Eigen::Isometry3d T = T_imu_lidar.ToIsometry();
  o.T_imu_lidar = lie::SE3d(lie::SO3d::FromMatrix(T.linear()), T.translation());
  return o;
}

std::string RunConfig::BackendName() const {
  return estimation::ToString(pipeline.estimator.backend);
}

logs::LogReadOptions RunConfig::LogOptions() const {
  logs::LogReadOptions options;
  options.lidar_topic = lidar.topic;
  options.imu_topic = pipeline.imu.enabled ? imu.topic : std::string();
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
  RejectDuplicateKeys(root, source_name);
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
  out.SetDoublePrecision(kYamlDoublePrecision);
  out << YAML::BeginMap;
  RunConfig copy = config;  // the visitor takes fields by non-const reference
  YamlWriteVisitor writer(&out);
  VisitFields(writer, copy);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void SaveRunConfig(const std::string& path, const RunConfig& config) {
  try {
    io::WriteFileAtomically(path, "# effective configuration written by hylo\n" + ToYaml(config));
  } catch (const std::runtime_error& e) {
    throw ConfigError(std::string("configuration file: ") + e.what());
  }
}

}  // namespace hylo::config
