// PLY reader (Greg Turk's polygon file format): ascii, binary_little_endian and
// binary_big_endian. Only the `vertex` element is decoded; the elements before it (rare)
// are read past, the ones after it (faces) are not read at all.

#include <cctype>
#include <cstdlib>

#include "cloud_fields.h"
#include "hylo/io/cloud_io.h"

namespace hylo::io {
namespace {

using internal::ScalarKind;
using internal::ScalarType;
using internal::ThrowFileError;

struct PlyProperty {
  std::string name;
  ScalarType type;
  bool is_list = false;
  ScalarType count_type;  ///< list length type (lists only)
  int slot = internal::kNone;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  std::string format;  ///< ascii, binary_little_endian or binary_big_endian
  std::vector<PlyElement> elements;
};

ScalarType ParsePlyType(const std::string& path, const std::string& name) {
  static const std::pair<const char*, ScalarType> kTypes[] = {
      {"char", {ScalarKind::kSigned, 1}},    {"int8", {ScalarKind::kSigned, 1}},
      {"uchar", {ScalarKind::kUnsigned, 1}}, {"uint8", {ScalarKind::kUnsigned, 1}},
      {"short", {ScalarKind::kSigned, 2}},   {"int16", {ScalarKind::kSigned, 2}},
      {"ushort", {ScalarKind::kUnsigned, 2}}, {"uint16", {ScalarKind::kUnsigned, 2}},
      {"int", {ScalarKind::kSigned, 4}},     {"int32", {ScalarKind::kSigned, 4}},
      {"uint", {ScalarKind::kUnsigned, 4}},  {"uint32", {ScalarKind::kUnsigned, 4}},
      {"float", {ScalarKind::kFloat, 4}},    {"float32", {ScalarKind::kFloat, 4}},
      {"double", {ScalarKind::kFloat, 8}},   {"float64", {ScalarKind::kFloat, 8}}};
  for (const auto& [type_name, type] : kTypes) {
    if (name == type_name) return type;
  }
  ThrowFileError(path, "malformed header: unknown PLY type '" + name + "'");
}

void AddProperty(const std::string& path, const std::vector<std::string>& words,
                 PlyHeader* header) {
  if (header->elements.empty()) ThrowFileError(path, "malformed header: property before element");
  PlyProperty p;
  if (words.size() == 5 && words[1] == "list") {
    p.is_list = true;
    p.count_type = ParsePlyType(path, words[2]);
    p.type = ParsePlyType(path, words[3]);
    p.name = words[4];
  } else if (words.size() == 3) {
    p.type = ParsePlyType(path, words[1]);
    p.name = words[2];
    p.slot = internal::SlotForName(p.name);
  } else {
    ThrowFileError(path, "malformed header: bad property line");
  }
  header->elements.back().properties.push_back(p);
}

PlyHeader ReadHeader(const std::string& path, std::ifstream* in) {
  std::string line;
  if (!std::getline(*in, line) || internal::SplitWords(line) != std::vector<std::string>{"ply"}) {
    ThrowFileError(path, "malformed header: does not start with 'ply'");
  }
  PlyHeader header;
  constexpr int kMaxHeaderLines = 10000;
  for (int n = 0; n < kMaxHeaderLines && std::getline(*in, line); ++n) {
    const std::vector<std::string> words = internal::SplitWords(line);
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "end_header") {
      if (header.format.empty()) ThrowFileError(path, "malformed header: no format line");
      return header;
    }
    if (words[0] == "format" && words.size() == 3) {
      header.format = words[1];
      if (header.format != "ascii" && header.format != "binary_little_endian" &&
          header.format != "binary_big_endian") {
        ThrowFileError(path, "malformed header: unknown format '" + header.format + "'");
      }
    } else if (words[0] == "element" && words.size() == 3) {
      PlyElement e;
      e.name = words[1];
      char* end = nullptr;
      e.count = std::strtoull(words[2].c_str(), &end, 10);
      // strtoull accepts "-1" (as 2^64 - 1): a count is digits only.
      if (*end != '\0' || !std::isdigit(static_cast<unsigned char>(words[2][0]))) {
        ThrowFileError(path, "malformed header: bad element count " + words[2]);
      }
      header.elements.push_back(e);
    } else if (words[0] == "property") {
      AddProperty(path, words, &header);
    } else {
      ThrowFileError(path, "malformed header: unexpected line '" + line + "'");
    }
  }
  ThrowFileError(path, "malformed header: no end_header line");
}

// Walks the body value by value; throws "truncated" when the file ends early.
class BodyCursor {
 public:
  BodyCursor(const std::string& path, const std::string& format, std::vector<uint8_t> body)
      : path_(path), ascii_(format == "ascii"), swap_(format == "binary_big_endian"),
        body_(std::move(body)) {
    if (ascii_) body_.push_back('\0');  // strtod stops at the terminator
  }

  double Next(ScalarType type) {
    if (ascii_) {
      const char* begin = reinterpret_cast<const char*>(body_.data()) + pos_;
      char* end = nullptr;
      const double value = std::strtod(begin, &end);
      if (end == begin) Fail();
      pos_ += static_cast<std::size_t>(end - begin);
      return internal::AsDeclared(value, type);
    }
    if (body_.size() - pos_ < static_cast<std::size_t>(type.size)) Fail();
    const double value = internal::DecodeScalar(body_.data() + pos_, type, swap_);
    pos_ += type.size;
    return value;
  }

  void Skip(const PlyProperty& p) {
    if (!p.is_list) {
      Next(p.type);
      return;
    }
    // Every value takes at least one byte, so a list longer than the bytes left is corrupt
    // (an ascii length may also be negative, NaN or 1e300).
    const double count = Next(p.count_type);
    if (!(count >= 0.0 && count <= static_cast<double>(body_.size() - pos_))) {
      ThrowFileError(path_, "corrupt: list length " + std::to_string(count) + " after " +
                                std::to_string(items_done) + " items");
    }
    for (std::size_t k = 0; k < static_cast<std::size_t>(count); ++k) Next(p.type);
  }

  std::size_t items_done = 0;

 private:
  [[noreturn]] void Fail() {
    ThrowFileError(path_, "truncated or malformed data after " + std::to_string(items_done) +
                              " items (header promises more)");
  }
  std::string path_;
  bool ascii_, swap_;
  std::vector<uint8_t> body_;
  std::size_t pos_ = 0;
};

CloudFile ReadVertices(const std::string& path, const PlyElement& vertex, BodyCursor* cursor) {
  bool present[internal::kNumSlots] = {};
  for (const PlyProperty& p : vertex.properties) {
    if (p.slot != internal::kNone) present[p.slot] = true;
  }
  internal::CloudBuilder builder(path, present, std::min<std::size_t>(vertex.count, 1 << 24));
  double record[internal::kNumSlots] = {};
  for (std::size_t i = 0; i < vertex.count; ++i, ++cursor->items_done) {
    for (const PlyProperty& p : vertex.properties) {
      if (p.slot == internal::kNone) {
        cursor->Skip(p);
      } else {
        record[p.slot] = cursor->Next(p.type);
      }
    }
    builder.Add(record);
  }
  return builder.Finish();
}

}  // namespace

CloudFile ReadPly(const std::string& path) {
  std::ifstream in = internal::OpenForReading(path);
  const PlyHeader header = ReadHeader(path, &in);
  BodyCursor cursor(path, header.format, internal::ReadRest(&in));
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex") return ReadVertices(path, element, &cursor);
    // An element without properties takes no bytes, however many it announces.
    if (element.properties.empty()) continue;
    for (std::size_t i = 0; i < element.count; ++i, ++cursor.items_done) {
      for (const PlyProperty& p : element.properties) cursor.Skip(p);
    }
  }
  ThrowFileError(path, "no vertex element");
}

CloudFileInfo ReadPlyInfo(const std::string& path) {
  std::ifstream in = internal::OpenForReading(path);
  const PlyHeader header = ReadHeader(path, &in);
  CloudFileInfo info;
  info.format = "ply";
  info.encoding = header.format;
  for (const PlyElement& element : header.elements) {
    if (element.name != "vertex") continue;
    info.points = element.count;
    for (const PlyProperty& p : element.properties) info.fields.push_back(p.name);
    return info;
  }
  ThrowFileError(path, "no vertex element");
}

}  // namespace hylo::io
