// Configuration given in parts: a preset with a few keys changed, a `ground:` section alone.
// Both end in the one reader (yaml_visitors.h), so keys, errors and validation are a run
// configuration's.
#include <yaml-cpp/yaml.h>

#include "hylo/config/run_config.h"
#include "run_config_fields.h"
#include "yaml_visitors.h"

namespace hylo::config {
namespace {

YAML::Node LoadMap(const std::string& text, const std::string& source_name) {
  YAML::Node node;
  try {
    node = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source_name + ": malformed YAML: " + e.what());
  }
  if (node.IsNull()) return YAML::Node(YAML::NodeType::Map);
  if (!node.IsMap()) throw ConfigError(source_name + ": expected a map of keys at the top level");
  return node;
}

// Sets every key of `overrides` in `base`: a map into a map merges key by key, anything else
// replaces what was there (a list, a scalar, `imu: none` over a section and back).
void MergeInto(YAML::Node base, const YAML::Node& overrides) {
  for (const auto& entry : overrides) {
    const std::string key = entry.first.as<std::string>();
    YAML::Node target = base[key];
    if (target.IsMap() && entry.second.IsMap()) {
      MergeInto(target, entry.second);
    } else {
      base[key] = YAML::Clone(entry.second);
    }
  }
}

}  // namespace

std::string MergeYaml(const std::string& base, const std::string& overrides,
                      const std::string& source_name) {
  YAML::Node merged = LoadMap(base, source_name);
  MergeInto(merged, LoadMap(overrides, source_name));
  YAML::Emitter out;
  out << merged;
  return std::string(out.c_str()) + "\n";
}

terrain::GroundFilterOptions ParseGroundOptions(const std::string& yaml_text,
                                                const std::string& source_name,
                                                terrain::GroundFilterOptions defaults) {
  const YAML::Node root = LoadMap(yaml_text, source_name);
  YamlReadVisitor reader(root, "ground", source_name);
  VisitFields(reader, defaults);
  reader.RejectUnknownKeys();
  std::string why;
  if (!defaults.IsValid(&why)) {
    throw ConfigError(source_name + ": invalid value: ground." + why);
  }
  return defaults;
}

}  // namespace hylo::config
