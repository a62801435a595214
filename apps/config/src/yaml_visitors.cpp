#include "yaml_visitors.h"

#include <sstream>

namespace hylo::config {
namespace {
std::string Describe(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a map";
  return "nothing";
}
}  // namespace

void YamlReadVisitor::Fail(const std::string& key_path, const std::string& reason) const {
  throw ConfigError(source_ + ": " + key_path + ": " + reason);
}

void YamlReadVisitor::RejectUnknownKeys() const {
  for (const auto& entry : node_) {
    const std::string key = entry.first.as<std::string>();
    if (used_.count(key) != 0) continue;
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

void YamlReadVisitor::Convert(const YAML::Node& node, const std::string& key_path,
                              io::PointTimeConvention* value) const {
  if (!node.IsScalar() || !io::ParsePointTimeConvention(node.Scalar(), value)) {
    Fail(key_path, "expected one of auto, velodyne, ouster, hesai, robosense, livox, none; got " +
                       Describe(node));
  }
}

void YamlReadVisitor::Convert(const YAML::Node& node, const std::string& key_path,
                              mapping::GroundMethod* value) const {
  if (!node.IsScalar() || !mapping::ParseGroundMethod(node.Scalar(), value)) {
    Fail(key_path, "expected smrf or csf; got " + Describe(node));
  }
}

void YamlReadVisitor::Convert(const YAML::Node& node, const std::string& key_path,
                              mapping::ClothHoleFill* value) const {
  if (!node.IsScalar() || !mapping::ParseClothHoleFill(node.Scalar(), value)) {
    Fail(key_path, "expected mean, nearest or reference; got " + Describe(node));
  }
}

}  // namespace hylo::config
