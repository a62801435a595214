#include "hylo/config/config_json.h"

#include <type_traits>

#include "enum_fields.h"
#include "run_config_fields.h"

namespace hylo::config {
namespace {

// nlohmann writes a non-finite double as null: "no limit" (an infinite gap) reads as null.
io::Json Value(double v) { return v; }
io::Json Value(int v) { return v; }
io::Json Value(bool v) { return v; }
io::Json Value(const std::string& v) { return v; }
io::Json Value(const Eigen::Vector3d& v) { return io::Json::array({v.x(), v.y(), v.z()}); }
template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
io::Json Value(E v) {
  return EnumField<E>::Name(v);
}

// Writes each field under its key, sections as nested objects, in the field list's order.
class JsonWriteVisitor {
 public:
  explicit JsonWriteVisitor(io::Json* out) : out_(out) {}

  template <class T>
  void operator()(const char* key, T& value, const char* /*description*/) {
    (*out_)[key] = Value(value);
  }

  template <class S>
  void Section(const char* key, S& section, const char* /*description*/) {
    (*out_)[key] = Write(section);
  }

  template <class S>
  void OptionalSection(const char* key, S& section, bool& enabled, const char* description) {
    if (enabled) {
      Section(key, section, description);
    } else {
      (*out_)[key] = "none";
    }
  }

  template <class S>
  static io::Json Write(S& section) {
    io::Json json = io::Json::object();
    JsonWriteVisitor writer(&json);
    VisitFields(writer, section);
    return json;
  }

 private:
  io::Json* out_;
};

}  // namespace

// The visitor takes fields by non-const reference (the reader shares the list): write copies.
io::Json ToJson(const RunConfig& config) {
  RunConfig copy = config;
  return JsonWriteVisitor::Write(copy);
}

io::Json ToJson(const terrain::GroundFilterOptions& options) {
  terrain::GroundFilterOptions copy = options;
  return JsonWriteVisitor::Write(copy);
}

io::Json ToJson(const terrain::ClothFilterOptions& options) {
  terrain::ClothFilterOptions copy = options;
  return JsonWriteVisitor::Write(copy);
}

io::Json ToJson(const terrain::SmrfOptions& options) {
  terrain::SmrfOptions copy = options;
  return JsonWriteVisitor::Write(copy);
}

}  // namespace hylo::config
