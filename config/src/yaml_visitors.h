#pragma once
// The two visitors that walk run_config_fields.h: one reads a YAML node into the structs
// (tracking which keys it used, so every other key is reported), one writes them back.

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>

#include "hylo/config/run_config.h"

namespace hylo::config {

class YamlReadVisitor {
 public:
  YamlReadVisitor(YAML::Node node, std::string path, std::string source)
      : node_(std::move(node)), path_(std::move(path)), source_(std::move(source)) {}

  template <class T>
  void operator()(const char* key, T& value) {
    used_.insert(key);
    const YAML::Node child = node_[key];
    if (child.IsDefined() && !child.IsNull()) Convert(child, Join(key), &value);
  }

  template <class S>
  void Section(const char* key, S& section) {
    used_.insert(key);
    const YAML::Node child = node_[key];
    if (!child.IsDefined() || child.IsNull()) return;
    if (!child.IsMap()) Fail(Join(key), "expected a map of keys");
    YamlReadVisitor nested(child, Join(key), source_);
    VisitFields(nested, section);
    nested.RejectUnknownKeys();
  }

  template <class S>
  void OptionalSection(const char* key, S& section, bool& enabled) {
    const YAML::Node child = node_[key];
    if (child.IsDefined() && child.IsScalar() && child.Scalar() == "none") {
      used_.insert(key);
      enabled = false;
      return;
    }
    enabled = true;
    Section(key, section);
  }

  /// Throws ConfigError for the first key of this map that no field consumed.
  void RejectUnknownKeys() const;

 private:
  std::string Join(const char* key) const { return path_.empty() ? key : path_ + "." + key; }
  [[noreturn]] void Fail(const std::string& key_path, const std::string& reason) const;

  void Convert(const YAML::Node& node, const std::string& key_path, double* value) const;
  void Convert(const YAML::Node& node, const std::string& key_path, int* value) const;
  void Convert(const YAML::Node& node, const std::string& key_path, bool* value) const;
  void Convert(const YAML::Node& node, const std::string& key_path, std::string* value) const;
  void Convert(const YAML::Node& node, const std::string& key_path, Eigen::Vector3d* value) const;
  void Convert(const YAML::Node& node, const std::string& key_path,
               logs::PointTimeConvention* value) const;
  void Convert(const YAML::Node& node, const std::string& key_path,
               estimation::Estimator::Backend* value) const;
  void Convert(const YAML::Node& node, const std::string& key_path,
               estimation::SlidingWindowOptions::LinearSolver* value) const;
  void Convert(const YAML::Node& node, const std::string& key_path,
               estimation::SlidingWindowOptions::RobustLoss* value) const;
  void Convert(const YAML::Node& node, const std::string& key_path,
               terrain::GroundMethod* value) const;
  void Convert(const YAML::Node& node, const std::string& key_path,
               terrain::ClothHoleFill* value) const;

  YAML::Node node_;
  std::string path_;
  std::string source_;
  std::set<std::string> used_;
};

class YamlWriteVisitor {
 public:
  explicit YamlWriteVisitor(YAML::Emitter* out) : out_(out) {}

  template <class T>
  void operator()(const char* key, T& value) {
    *out_ << YAML::Key << key << YAML::Value;
    Emit(value);
  }

  template <class S>
  void Section(const char* key, S& section) {
    *out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
    VisitFields(*this, section);
    *out_ << YAML::EndMap;
  }

  template <class S>
  void OptionalSection(const char* key, S& section, bool& enabled) {
    if (enabled) {
      Section(key, section);
    } else {
      *out_ << YAML::Key << key << YAML::Value << "none";
    }
  }

 private:
  void Emit(double value) { *out_ << value; }
  void Emit(int value) { *out_ << value; }
  void Emit(bool value) { *out_ << value; }
  void Emit(const std::string& value) { *out_ << value; }
  void Emit(const Eigen::Vector3d& value) {
    *out_ << YAML::Flow << YAML::BeginSeq << value.x() << value.y() << value.z() << YAML::EndSeq;
  }
  void Emit(logs::PointTimeConvention value) { *out_ << logs::ToString(value); }
  void Emit(estimation::Estimator::Backend value) { *out_ << estimation::ToString(value); }
  void Emit(estimation::SlidingWindowOptions::LinearSolver value) {
    *out_ << estimation::ToString(value);
  }
  void Emit(estimation::SlidingWindowOptions::RobustLoss value) {
    *out_ << estimation::ToString(value);
  }
  void Emit(terrain::GroundMethod value) { *out_ << terrain::ToString(value); }
  void Emit(terrain::ClothHoleFill value) { *out_ << terrain::ToString(value); }

  YAML::Emitter* out_;
};

}  // namespace hylo::config
