#pragma once
// A small JSON value for the machine-readable summaries (`--json PATH`) and manifests.
// Objects keep insertion order so summaries read top-down like the terminal output.

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace hylo::io {

class Json {
 public:
  using Array = std::vector<Json>;
  using Object = std::vector<std::pair<std::string, Json>>;

  Json() = default;  // null
  Json(std::nullptr_t) {}
  Json(bool b) : value_(b) {}
  Json(int v) : value_(static_cast<int64_t>(v)) {}
  Json(long v) : value_(static_cast<int64_t>(v)) {}
  Json(long long v) : value_(static_cast<int64_t>(v)) {}
  Json(unsigned v) : value_(static_cast<int64_t>(v)) {}
  Json(unsigned long v) : value_(static_cast<int64_t>(v)) {}
  Json(unsigned long long v) : value_(static_cast<int64_t>(v)) {}
  Json(double v) : value_(v) {}
  Json(float v) : value_(static_cast<double>(v)) {}
  Json(const char* s) : value_(std::string(s)) {}
  Json(std::string s) : value_(std::move(s)) {}
  Json(Array a) : value_(std::move(a)) {}
  Json(Object o) : value_(std::move(o)) {}

  static Json MakeObject() { return Json(Object{}); }
  static Json MakeArray() { return Json(Array{}); }
  /// An array of numbers, for vectors, matrices (row-major) and per-item series.
  static Json FromNumbers(const std::vector<double>& values);

  /// Object member access; a null value becomes an object, a missing key is appended.
  Json& operator[](const std::string& key);
  /// Appends to an array; a null value becomes an array.
  void PushBack(Json value);

  bool IsNull() const { return std::holds_alternative<std::monostate>(value_); }
  bool IsObject() const { return std::holds_alternative<Object>(value_); }
  bool IsArray() const { return std::holds_alternative<Array>(value_); }
  const Object* AsObject() const { return std::get_if<Object>(&value_); }
  const Array* AsArray() const { return std::get_if<Array>(&value_); }
  const std::string* AsString() const { return std::get_if<std::string>(&value_); }
  /// Number value (int or double), or `fallback` when this is not a number.
  double AsNumber(double fallback = 0.0) const;
  /// Member lookup without insertion; nullptr when absent or not an object.
  const Json* Find(const std::string& key) const;

  /// Serialises; indent < 0 writes one line. Non-finite doubles are written as null
  /// (JSON has no NaN), so a summary stays parseable.
  std::string Dump(int indent = 2) const;

 private:
  void DumpTo(std::string* out, int indent, int depth) const;
  std::variant<std::monostate, bool, int64_t, double, std::string, Array, Object> value_;
};

/// Writes `json` to `path` (throws std::runtime_error naming the file on failure).
void WriteJsonFile(const std::string& path, const Json& json);

}  // namespace hylo::io
