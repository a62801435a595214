// Targets as YAML: a list of maps with the CSV's column names as keys, under `targets:` or
// bare. yaml-cpp is private to this file.
#include <yaml-cpp/yaml.h>

#include <map>
#include <set>

#include "hylo/io/targets_io.h"
#include "hylo/io/text.h"
#include "targets_fields.h"

namespace hylo::io {
namespace {

using targets::Key;

std::string At(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return "in the document";
  return "line " + std::to_string(mark.line + 1) + ", column " + std::to_string(mark.column + 1);
}

inspection::Target ReadOne(const std::string& path, const YAML::Node& node, std::set<Key>* given) {
  if (!node.IsMap()) ThrowFileError(path, At(node) + ": expected a map of keys (id, x, y, z, ...)");
  inspection::Target target;
  for (const auto& entry : node) {
    const YAML::Node& key_node = entry.first;
    const YAML::Node& value = entry.second;
    Key key;
    if (!key_node.IsScalar() || !targets::KeyOf(key_node.Scalar(), &key)) {
      ThrowFileError(path, At(key_node) + ": unknown key '" +
                               targets::Printable(key_node.IsScalar() ? key_node.Scalar() : "?") +
                               "' (expected among: " + targets::KeyNames() + ")");
    }
    if (!given->insert(key).second)
      ThrowFileError(path, At(key_node) + ": key '" + targets::NameOf(key) + "' given twice");
    if (!value.IsScalar()) {
      ThrowFileError(path, At(value) + " (" + targets::NameOf(key) + "): expected a single value");
    }
    if (key == Key::kId) {
      target.id = value.Scalar();
      continue;
    }
    double number;
    if (!targets::ParseFinite(value.Scalar(), &number)) {
      ThrowFileError(path, At(value) + " (" + targets::NameOf(key) + "): '" +
                               targets::Printable(value.Scalar()) + "' is not a finite number");
    }
    targets::Assign(key, number, &target);
  }
  return target;
}

}  // namespace

std::vector<inspection::Target> ReadTargetsYaml(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    ThrowFileError(path, "cannot open (missing or unreadable)");
  } catch (const YAML::Exception& e) {
    ThrowFileError(path, "line " + std::to_string(e.mark.line + 1) + ", column " +
                             std::to_string(e.mark.column + 1) + ": malformed YAML: " +
                             targets::Printable(e.msg));
  }
  YAML::Node list = root;
  if (root.IsMap()) {
    for (const auto& entry : root) {
      if (!entry.first.IsScalar() || entry.first.Scalar() != "targets") {
        ThrowFileError(path, At(entry.first) + ": unknown key (the file holds `targets:`, a list)");
      }
    }
    list = root["targets"];
  }
  if (!list || !list.IsSequence()) {
    ThrowFileError(path, At(list ? list : root) + ": expected a list of targets (or `targets:` "
                                                  "holding one)");
  }
  std::vector<inspection::Target> out;
  std::map<std::string, std::string> first_seen;
  for (const YAML::Node& node : list) {
    std::set<Key> given;
    const inspection::Target target = ReadOne(path, node, &given);
    targets::Finish(path, At(node), given, target, &first_seen);
    out.push_back(target);
  }
  if (out.empty()) ThrowFileError(path, "no target in the list");
  return out;
}

}  // namespace hylo::io
