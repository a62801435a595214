#include "hylo/io/json.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace hylo::io {
namespace {
void AppendEscaped(std::string* out, const std::string& s) {
  out->push_back('"');
  for (unsigned char c : s) {
    switch (c) {
      case '"': *out += "\\\""; break;
      case '\\': *out += "\\\\"; break;
      case '\n': *out += "\\n"; break;
      case '\r': *out += "\\r"; break;
      case '\t': *out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          *out += buf;
        } else {
          out->push_back(static_cast<char>(c));
        }
    }
  }
  out->push_back('"');
}

void AppendNewline(std::string* out, int indent, int depth) {
  if (indent < 0) return;
  out->push_back('\n');
  out->append(static_cast<std::size_t>(indent * depth), ' ');
}
}  // namespace

Json Json::FromNumbers(const std::vector<double>& values) {
  Array a;
  a.reserve(values.size());
  for (double v : values) a.emplace_back(v);
  return Json(std::move(a));
}

Json& Json::operator[](const std::string& key) {
  if (IsNull()) value_ = Object{};
  auto& object = std::get<Object>(value_);  // throws std::bad_variant_access if misused
  for (auto& [k, v] : object) {
    if (k == key) return v;
  }
  object.emplace_back(key, Json());
  return object.back().second;
}

void Json::PushBack(Json value) {
  if (IsNull()) value_ = Array{};
  std::get<Array>(value_).push_back(std::move(value));
}

double Json::AsNumber(double fallback) const {
  if (const auto* i = std::get_if<int64_t>(&value_)) return static_cast<double>(*i);
  if (const auto* d = std::get_if<double>(&value_)) return *d;
  return fallback;
}

const Json* Json::Find(const std::string& key) const {
  const Object* object = AsObject();
  if (object == nullptr) return nullptr;
  for (const auto& [k, v] : *object) {
    if (k == key) return &v;
  }
  return nullptr;
}

std::string Json::Dump(int indent) const {
  std::string out;
  DumpTo(&out, indent, 0);
  return out;
}

void Json::DumpTo(std::string* out, int indent, int depth) const {
  if (IsNull()) {
    *out += "null";
  } else if (const auto* b = std::get_if<bool>(&value_)) {
    *out += *b ? "true" : "false";
  } else if (const auto* i = std::get_if<int64_t>(&value_)) {
    *out += std::to_string(*i);
  } else if (const auto* d = std::get_if<double>(&value_)) {
    if (!std::isfinite(*d)) {
      *out += "null";
    } else {
      char buf[32];
      std::snprintf(buf, sizeof(buf), "%.10g", *d);
      *out += buf;
    }
  } else if (const auto* s = std::get_if<std::string>(&value_)) {
    AppendEscaped(out, *s);
  } else if (const auto* a = std::get_if<Array>(&value_)) {
    out->push_back('[');
    for (std::size_t n = 0; n < a->size(); ++n) {
      if (n > 0) out->push_back(',');
      AppendNewline(out, indent, depth + 1);
      (*a)[n].DumpTo(out, indent, depth + 1);
    }
    if (!a->empty()) AppendNewline(out, indent, depth);
    out->push_back(']');
  } else if (const auto* o = std::get_if<Object>(&value_)) {
    out->push_back('{');
    for (std::size_t n = 0; n < o->size(); ++n) {
      if (n > 0) out->push_back(',');
      AppendNewline(out, indent, depth + 1);
      AppendEscaped(out, (*o)[n].first);
      *out += indent < 0 ? ":" : ": ";
      (*o)[n].second.DumpTo(out, indent, depth + 1);
    }
    if (!o->empty()) AppendNewline(out, indent, depth);
    out->push_back('}');
  }
}

void WriteJsonFile(const std::string& path, const Json& json) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write JSON file '" + path + "'");
  file << json.Dump(2) << '\n';
  if (!file) throw std::runtime_error("failed while writing JSON file '" + path + "'");
}

}  // namespace hylo::io
