#pragma once
// A key given twice in one YAML map. yaml-cpp keeps both entries and a lookup finds one of
// them, so a repeated key would silently override (or be overridden by) the other; a
// configuration states each setting once.

#include <yaml-cpp/yaml.h>

#include <string>

namespace hylo::config {

/// Throws ConfigError naming `source`, the key path and the lines of both occurrences when any
/// map, at any depth, holds a key twice (the first such map met depth first). Keys that are
/// not scalars are left to the unknown-key check.
void RejectDuplicateKeys(const YAML::Node& root, const std::string& source);

}  // namespace hylo::config
