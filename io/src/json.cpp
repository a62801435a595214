#include "hylo/io/json.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "hylo/io/atomic_file.h"

namespace hylo::io {
namespace {

// nlohmann's messages start with an id ("[json.exception.parse_error.101] "); the rest says
// what went wrong in words.
std::string WithoutExceptionId(const char* what) {
  const std::string text = what;
  const std::size_t end = text.find("] ");
  return text.rfind("[json.exception.", 0) == 0 && end != std::string::npos ? text.substr(end + 2)
                                                                            : text;
}

}  // namespace

std::string DumpJson(const Json& json, int indent) {
  return json.dump(indent, ' ', /*ensure_ascii=*/false, Json::error_handler_t::replace);
}

void WriteJsonFile(const std::string& path, const Json& json) {
  WriteFileAtomically(path, DumpJson(json, 2) + '\n');
}

Json ReadJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("'" + path + "': cannot open (missing or unreadable)");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw std::runtime_error("'" + path + "': read failed");
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    throw std::runtime_error("'" + path + "': not valid JSON at byte " + std::to_string(e.byte) +
                             ": " + WithoutExceptionId(e.what()));
  } catch (const Json::out_of_range& e) {
    // A number beyond double's range ("1E400") is reported as out of range, without a byte.
    throw std::runtime_error("'" + path + "': not valid JSON: " + WithoutExceptionId(e.what()));
  }
}

double NumberAt(const Json& json, const std::string& dotted_path) {
  const Json* node = &json;
  std::size_t begin = 0;
  while (true) {
    const std::size_t dot = dotted_path.find('.', begin);
    if (!node->is_object()) return std::numeric_limits<double>::quiet_NaN();
    const auto member = node->find(dotted_path.substr(begin, dot - begin));
    if (member == node->end()) return std::numeric_limits<double>::quiet_NaN();
    node = &*member;
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  return node->is_number() ? node->get<double>() : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace hylo::io
