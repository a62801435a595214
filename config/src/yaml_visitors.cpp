#include "yaml_visitors.h"

#include <sstream>

#include "config_sections.h"

namespace hylo::config {
namespace {

std::string Describe(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a map";
  return "nothing";
}

}  // namespace

const char* MovedKeyHint(const std::string& key_path) {
  struct Moved {
    const char* old_path;
    const char* hint;
  };
  static const Moved kMoved[] = {
      {"lidar.min_range_m", "moved to preprocess.min_range_m"},
      {"lidar.max_range_m", "moved to preprocess.max_range_m"},
      {"lidar.scan_period_s", "removed: a sweep's duration comes from its points' times"},
      {"map.prior_resolution_m", "moved to prior_map.resolution_m"},
      {"map.update_after_s", "moved to localization.update_after_s"},
      {"localization.health_max_points",
       "removed: the health check reads the update's residual of every point"},
      {"ieskf.lidar_noise_m", "moved to lidar_update.lidar_noise_m (both back-ends)"},
      {"sliding_window.lidar_noise_m", "moved to lidar_update.lidar_noise_m (both back-ends)"},
      {"ieskf.min_matches", "moved to lidar_update.min_matches (both back-ends)"},
      {"sliding_window.min_matches", "moved to lidar_update.min_matches (both back-ends)"},
      {"ieskf.min_translation_information", "moved to lidar_update.min_translation_information"},
      {"sliding_window.min_translation_information",
       "moved to lidar_update.min_translation_information"},
      {"ieskf.min_rotation_information", "moved to lidar_update.min_rotation_information"},
      {"sliding_window.min_rotation_information", "moved to lidar_update.min_rotation_information"},
      {"ieskf.cv_translation_noise", "moved to no_imu.cv_translation_noise (both back-ends)"},
      {"sliding_window.cv_translation_noise", "moved to no_imu.cv_translation_noise"},
      {"ieskf.cv_rotation_noise", "moved to no_imu.cv_rotation_noise (both back-ends)"},
      {"sliding_window.cv_rotation_noise", "moved to no_imu.cv_rotation_noise"},
      {"ieskf.no_imu_yaw_search_deg", "moved to no_imu.yaw_search_deg (both back-ends)"},
      {"sliding_window.no_imu_yaw_search_deg", "moved to no_imu.yaw_search_deg"},
      {"ieskf.no_imu_yaw_search_step_deg", "moved to no_imu.yaw_search_step_deg"},
      {"sliding_window.no_imu_yaw_search_step_deg", "moved to no_imu.yaw_search_step_deg"},
      {"ieskf.init_rotation_sigma_rad", "moved to initial_uncertainty.rotation_sigma_rad"},
      {"ieskf.init_velocity_sigma_mps", "moved to initial_uncertainty.velocity_sigma_mps"},
      {"ieskf.init_gyro_bias_sigma_radps", "moved to initial_uncertainty.gyro_bias_sigma_radps"},
      {"ieskf.init_accel_bias_sigma_mps2", "moved to initial_uncertainty.accel_bias_sigma_mps2"},
      {"ieskf.init_gravity_sigma_mps2", "moved to initial_uncertainty.gravity_sigma_mps2"},
      {"ieskf.init_extrinsic_rotation_sigma_rad",
       "moved to initial_uncertainty.extrinsic_rotation_sigma_rad"},
      {"ieskf.init_extrinsic_translation_sigma_m",
       "moved to initial_uncertainty.extrinsic_translation_sigma_m"},
  };
  for (const Moved& m : kMoved) {
    if (key_path == m.old_path) return m.hint;
  }
  return nullptr;
}

void YamlReadVisitor::Fail(const std::string& key_path, const std::string& reason) const {
  throw ConfigError(source_ + ": " + key_path + ": " + reason);
}

void YamlReadVisitor::RejectUnknownKeys() const {
  for (const auto& entry : node_) {
    // YAML allows a list or a map as a key ("{[a]: 1}"); none is a key of ours.
    if (!entry.first.IsScalar()) {
      Fail(path_.empty() ? "top level" : path_, "a key that is " + Describe(entry.first));
    }
    const std::string key = entry.first.as<std::string>();
    if (used_.count(key) != 0) continue;
    if (const char* hint = MovedKeyHint(Join(key.c_str()))) {
      Fail(Join(key.c_str()), std::string("unknown key (") + hint + ")");
    }
    std::ostringstream known;
    for (const auto& k : used_) known << (known.tellp() > 0 ? ", " : "") << k;
    Fail(Join(key.c_str()), "unknown key (known keys here: " + known.str() + ")");
  }
}

void YamlReadVisitor::Convert(const YAML::Node& node, const std::string& key_path,
                              double* value) const {
  if (!node.IsScalar()) Fail(key_path, "expected a number, got " + Describe(node));
  try {
    *value = node.as<double>();
  } catch (const YAML::Exception&) {
    Fail(key_path, "expected a number, got " + Describe(node));
  }
}

void YamlReadVisitor::Convert(const YAML::Node& node, const std::string& key_path,
                              int* value) const {
  if (!node.IsScalar()) Fail(key_path, "expected an integer, got " + Describe(node));
  try {
    *value = node.as<int>();
  } catch (const YAML::Exception&) {
    Fail(key_path, "expected an integer, got " + Describe(node));
  }
}

void YamlReadVisitor::Convert(const YAML::Node& node, const std::string& key_path,
                              bool* value) const {
  if (!node.IsScalar()) Fail(key_path, "expected true or false, got " + Describe(node));
  try {
    *value = node.as<bool>();
  } catch (const YAML::Exception&) {
    Fail(key_path, "expected true or false, got " + Describe(node));
  }
}

void YamlReadVisitor::Convert(const YAML::Node& node, const std::string& key_path,
                              std::string* value) const {
  if (!node.IsScalar()) Fail(key_path, "expected a string, got " + Describe(node));
  *value = node.Scalar();
}

void YamlReadVisitor::Convert(const YAML::Node& node, const std::string& key_path,
                              Eigen::Vector3d* value) const {
  if (!node.IsSequence() || node.size() != 3) {
    Fail(key_path, "expected a list of 3 numbers, got " + Describe(node));
  }
  for (int i = 0; i < 3; ++i) Convert(node[i], key_path + "[" + std::to_string(i) + "]",
                                      &(*value)[i]);
}

void YamlReadVisitor::FailEnum(const YAML::Node& node, const std::string& key_path,
                               const std::vector<std::string>& names) const {
  Fail(key_path, "expected " + JoinAlternatives(names) + "; got " + Describe(node));
}

}  // namespace hylo::config
