#pragma once
// Enums that appear in configuration files and summaries are written by name. Each such enum
// keeps one table of {value, name} pairs; these two lookups read it both ways.

#include <cstddef>
#include <string>
#include <utility>

namespace hylo {

/// The name of `value` in `names`, or "unknown".
template <class E, std::size_t N>
std::string NameOf(const std::pair<E, const char*> (&names)[N], E value) {
  for (const auto& [e, name] : names) {
    if (e == value) return name;
  }
  return "unknown";
}

/// The value named `name` into *value; false when no entry has that name.
template <class E, std::size_t N>
bool ValueOf(const std::pair<E, const char*> (&names)[N], const std::string& name, E* value) {
  for (const auto& [e, n] : names) {
    if (name == n) {
      *value = e;
      return true;
    }
  }
  return false;
}

/// "a, b or c": the names of a table, for error messages.
template <class E, std::size_t N>
std::string NameList(const std::pair<E, const char*> (&names)[N]) {
  std::string list;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) list += i + 1 == N ? " or " : ", ";
    list += names[i].second;
  }
  return list;
}

}  // namespace hylo
