#include "duplicate_keys.h"

#include <map>
#include <set>
#include <utility>
#include <vector>

#include "hylo/config/run_config.h"

namespace hylo::config {
namespace {

// "line 3 and line 7", or with columns when both are on one line (a flow map).
std::string Where(const YAML::Mark& first, const YAML::Mark& second) {
  if (first.line == second.line) {
    return "line " + std::to_string(first.line + 1) + ", columns " +
           std::to_string(first.column + 1) + " and " + std::to_string(second.column + 1);
  }
  return "line " + std::to_string(first.line + 1) + " and line " + std::to_string(second.line + 1);
}

std::string Join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

}  // namespace

void RejectDuplicateKeys(const YAML::Node& root, const std::string& source) {
  // Depth first with an explicit stack: a file may nest deeper than the call stack would like.
  // An alias makes a node reachable twice, even from inside itself (`a: &x [*x]`), so each
  // collection is visited once, known by where it starts and its kind.
  std::vector<std::pair<YAML::Node, std::string>> stack{{root, ""}};
  std::set<std::pair<int, int>> visited;
  while (!stack.empty()) {
    const auto [node, path] = stack.back();
    stack.pop_back();
    if (!node.IsMap() && !node.IsSequence()) continue;
    if (!visited.insert({node.Mark().pos, static_cast<int>(node.Type())}).second) continue;
    std::vector<std::pair<YAML::Node, std::string>> children;
    if (node.IsSequence()) {
      std::size_t i = 0;
      for (const YAML::Node& child : node) {
        children.emplace_back(child, path + "[" + std::to_string(i++) + "]");
      }
    } else {
      std::map<std::string, YAML::Mark> seen;
      for (const auto& entry : node) {
        if (!entry.first.IsScalar()) continue;
        const std::string& key = entry.first.Scalar();
        const auto [it, inserted] = seen.emplace(key, entry.first.Mark());
        if (!inserted) {
          throw ConfigError(source + ": " + Join(path, key) + ": the key is given twice (" +
                            Where(it->second, entry.first.Mark()) + ")");
        }
        children.emplace_back(entry.second, Join(path, key));
      }
    }
    // Pushed in reverse so the first duplicate in document order is the one reported.
    stack.insert(stack.end(), children.rbegin(), children.rend());
  }
}

}  // namespace hylo::config
