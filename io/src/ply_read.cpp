// PLY reader (Greg Turk's polygon file format): ascii, binary_little_endian and
// binary_big_endian, read in chunks (cloud_stream.h); ReadPly drains one stream. Only the
// `vertex` element is decoded.

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <memory>

#include "cloud_fields.h"
#include "cloud_streams.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/cloud_stream.h"

namespace hylo::io {
namespace {

using internal::ScalarKind;
using internal::ScalarType;


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
      {"char", {ScalarKind::kSigned, 1}},     {"int8", {ScalarKind::kSigned, 1}},
      {"uchar", {ScalarKind::kUnsigned, 1}},  {"uint8", {ScalarKind::kUnsigned, 1}},
      {"short", {ScalarKind::kSigned, 2}},    {"int16", {ScalarKind::kSigned, 2}},
      {"ushort", {ScalarKind::kUnsigned, 2}}, {"uint16", {ScalarKind::kUnsigned, 2}},
      {"int", {ScalarKind::kSigned, 4}},      {"int32", {ScalarKind::kSigned, 4}},
      {"uint", {ScalarKind::kUnsigned, 4}},   {"uint32", {ScalarKind::kUnsigned, 4}},
      {"float", {ScalarKind::kFloat, 4}},     {"float32", {ScalarKind::kFloat, 4}},
      {"double", {ScalarKind::kFloat, 8}},    {"float64", {ScalarKind::kFloat, 8}}};
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
  if (!std::getline(*in, line) || SplitWords(line) != std::vector<std::string>{"ply"}) {
    ThrowFileError(path, "malformed header: does not start with 'ply'");
  }
  PlyHeader header;
  constexpr int kMaxHeaderLines = 10000;
  for (int n = 0; n < kMaxHeaderLines && std::getline(*in, line); ++n) {
    const std::vector<std::string> words = SplitWords(line);
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
  BodyCursor(const std::string& path, const std::string& format, std::ifstream* in)
      : path_(path), ascii_(format == "ascii"), swap_(format == "binary_big_endian"), reader_(in) {}

  double Next(ScalarType type) {
    if (ascii_) {
      if (!reader_.NextWord(&word_)) Fail();
      char* end = nullptr;
      const double value = std::strtod(word_.c_str(), &end);
      if (end != word_.c_str() + word_.size()) Fail();
      return internal::AsDeclared(value, type);
    }
    uint8_t bytes[8];
    if (!reader_.Read(bytes, static_cast<std::size_t>(type.size))) Fail();
    return internal::DecodeScalar(bytes, type, swap_);
  }

  void Skip(const PlyProperty& p) {
    if (!p.is_list) {
      Next(p.type);
      return;
    }
    const double count = Next(p.count_type);
    // An ascii length may also be NaN or 1e300; PLY's widest count type is a 32-bit integer.
    if (!(count >= 0.0 && count <= static_cast<double>(UINT32_MAX))) {
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
  internal::BufferedReader reader_;
  std::string word_;
};

// The vertex element, read in chunks; the elements before it (rare) are read past when the
// stream opens, the ones after it (faces) are not read at all.
class PlyStream final : public CloudStream {
 public:
  explicit PlyStream(const std::string& path)
      : CloudStream(path), in_(internal::OpenForReading(path)) {
    header_ = ReadHeader(path, &in_);
    cursor_ = std::make_unique<BodyCursor>(path, header_.format, &in_);
    for (const PlyElement& element : header_.elements) {
      if (element.name == "vertex") {
        vertex_ = element;
        break;
      }
      // An element without properties takes no bytes, however many it announces.
      if (element.properties.empty()) continue;
      for (std::size_t i = 0; i < element.count; ++i, ++cursor_->items_done) {
        for (const PlyProperty& p : element.properties) cursor_->Skip(p);
      }
    }
    if (vertex_.name.empty()) ThrowFileError(path, "no vertex element");
    info_.format = "ply";
    info_.encoding = header_.format;
    info_.points = vertex_.count;
    for (const PlyProperty& p : vertex_.properties) {
      info_.fields.push_back(p.name);
      if (p.slot != internal::kNone) present_[p.slot] = true;
    }
    internal::CloudBuilder check(path, present_, 0);  // x, y and z must be there
  }

  bool Next(std::size_t max_points, CloudFile* chunk) override {
    *chunk = CloudFile();
    const std::size_t n = std::min(max_points, vertex_.count - records_read_);
    if (n == 0) return false;
    // The count is not checked against the file's size: reserve modestly.
    internal::CloudBuilder builder(path_, present_, std::min<std::size_t>(n, 1 << 24));
    double record[internal::kNumSlots] = {};
    for (std::size_t i = 0; i < n; ++i, ++cursor_->items_done) {
      for (const PlyProperty& p : vertex_.properties) {
        if (p.slot == internal::kNone) {
          cursor_->Skip(p);
        } else {
          record[p.slot] = cursor_->Next(p.type);
        }
      }
      builder.Add(record);
    }
    *chunk = builder.Finish();
    records_read_ += n;
    return true;
  }

 private:
  std::ifstream in_;
  PlyHeader header_;
  std::unique_ptr<BodyCursor> cursor_;
  PlyElement vertex_;
  bool present_[internal::kNumSlots] = {};
};

}  // namespace

std::unique_ptr<CloudStream> internal::OpenPlyStream(const std::string& path) {
  return std::make_unique<PlyStream>(path);
}

CloudFile ReadPly(const std::string& path) { return ReadAll(internal::OpenPlyStream(path).get()); }

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
