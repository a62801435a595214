#pragma once
// The two YAML visitors that walk run_config_fields.h: one reads a YAML node into the structs
// (tracking which keys it used, so every other key is reported), one writes them back. The
// descriptions the field list carries are for the reference doc; both ignore them.

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "enum_fields.h"
#include "hylo/config/run_config.h"

namespace hylo::config {

class YamlReadVisitor {
 public:
  YamlReadVisitor(YAML::Node node, std::string path, std::string source)
      : node_(std::move(node)), path_(std::move(path)), source_(std::move(source)) {}

  template <class T>
  void operator()(const char* key, T& value, const char* /*description*/) {
    used_.insert(key);
    const YAML::Node child = node_[key];
    if (child.IsDefined() && !child.IsNull()) Convert(child, Join(key), &value);
  }

  template <class S>
  void Section(const char* key, S& section, const char* /*description*/) {
    used_.insert(key);
    const YAML::Node child = node_[key];
    if (!child.IsDefined() || child.IsNull()) return;
    if (!child.IsMap()) Fail(Join(key), "expected a map of keys");
    YamlReadVisitor nested(child, Join(key), source_);
    VisitFields(nested, section);
    nested.RejectUnknownKeys();
  }

  template <class S>
  void OptionalSection(const char* key, S& section, bool& enabled, const char* description) {
    const YAML::Node child = node_[key];
    if (child.IsDefined() && child.IsScalar() && child.Scalar() == "none") {
      used_.insert(key);
      enabled = false;
      return;
    }
    enabled = true;
    Section(key, section, description);
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
  template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
  void Convert(const YAML::Node& node, const std::string& key_path, E* value) const {
    if (!node.IsScalar() || !EnumField<E>::Parse(node.Scalar(), value)) {
      FailEnum(node, key_path, EnumNames<E>());
    }
  }
  [[noreturn]] void FailEnum(const YAML::Node& node, const std::string& key_path,
                             const std::vector<std::string>& names) const;

  YAML::Node node_;
  std::string path_;
  std::string source_;
  std::set<std::string> used_;
};

/// One value as the YAML writer emits it (a flow list for vectors, names for enums).
inline void EmitYaml(YAML::Emitter* out, double value) { *out << value; }
inline void EmitYaml(YAML::Emitter* out, int value) { *out << value; }
inline void EmitYaml(YAML::Emitter* out, bool value) { *out << value; }
inline void EmitYaml(YAML::Emitter* out, const std::string& value) { *out << value; }
inline void EmitYaml(YAML::Emitter* out, const Eigen::Vector3d& value) {
  *out << YAML::Flow << YAML::BeginSeq << value.x() << value.y() << value.z() << YAML::EndSeq;
}
template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
void EmitYaml(YAML::Emitter* out, E value) {
  *out << EnumField<E>::Name(value);
}

/// The digits every written configuration keeps: enough that a value loads back unchanged.
constexpr int kYamlDoublePrecision = 10;

class YamlWriteVisitor {
 public:
  explicit YamlWriteVisitor(YAML::Emitter* out) : out_(out) {}

  template <class T>
  void operator()(const char* key, T& value, const char* /*description*/) {
    *out_ << YAML::Key << key << YAML::Value;
    EmitYaml(out_, value);
  }

  template <class S>
  void Section(const char* key, S& section, const char* /*description*/) {
    *out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
    VisitFields(*this, section);
    *out_ << YAML::EndMap;
  }

  template <class S>
  void OptionalSection(const char* key, S& section, bool& enabled, const char* description) {
    if (enabled) {
      Section(key, section, description);
    } else {
      *out_ << YAML::Key << key << YAML::Value << "none";
    }
  }

 private:
  YAML::Emitter* out_;
};

}  // namespace hylo::config
