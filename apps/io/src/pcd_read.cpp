// PCD v0.7 reader: ascii, binary (point-major) and binary_compressed (LZF, field-major).
// The header grammar follows the PCL file format description (pointclouds.org,
// "The PCD (Point Cloud Data) file format").

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include "cloud_fields.h"
#include "hylo/io/cloud_io.h"
#include "pcd_lzf.h"

namespace hylo::io {
namespace {

using internal::ScalarKind;
using internal::ScalarType;
using internal::ThrowFileError;

struct PcdField {
  std::string name;
  ScalarType type;
  std::size_t count = 1;
  std::size_t offset = 0;  ///< bytes from the start of a point record (binary layout)
  int slot = internal::kNone;
};

struct PcdHeader {
  std::vector<PcdField> fields;
  std::size_t width = 0;
  std::size_t height = 1;
  std::size_t points = 0;
  std::string data;            ///< ascii, binary or binary_compressed
  std::size_t point_step = 0;  ///< bytes per point record
  std::size_t FieldBytes(const PcdField& f) const { return f.type.size * f.count; }
};

std::size_t ParseCount(const std::string& path, const std::string& key, const std::string& word) {
  std::size_t value = 0;
  const auto result = std::from_chars(word.data(), word.data() + word.size(), value);
  if (result.ec != std::errc() || result.ptr != word.data() + word.size()) {
    ThrowFileError(path, "malformed header: " + key + " value '" + word + "' is not a count");
  }
  return value;
}

ScalarType ParseType(const std::string& path, const std::string& type, std::size_t size) {
  ScalarType t;
  t.size = static_cast<int>(size);
  const bool int_size = size == 1 || size == 2 || size == 4 || size == 8;
  if (type == "F" && (size == 4 || size == 8)) {
    t.kind = ScalarKind::kFloat;
  } else if (type == "I" && int_size) {
    t.kind = ScalarKind::kSigned;
  } else if (type == "U" && int_size) {
    t.kind = ScalarKind::kUnsigned;
  } else {
    ThrowFileError(
        path, "malformed header: unsupported TYPE " + type + " with SIZE " + std::to_string(size));
  }
  return t;
}

struct RawHeader {
  std::vector<std::string> names, sizes, types, counts;
  bool has_width = false, has_points = false;
};

void ApplyHeaderLine(const std::string& path, const std::vector<std::string>& words, RawHeader* raw,
                     PcdHeader* header) {
  const std::string key = words[0];
  const std::vector<std::string> values(words.begin() + 1, words.end());
  auto single = [&]() {
    if (values.size() != 1) ThrowFileError(path, "malformed header: " + key + " needs 1 value");
    return ParseCount(path, key, values[0]);
  };
  if (key == "VERSION" || key == "VIEWPOINT") return;  // the viewpoint is not applied
  if (key == "FIELDS" || key == "COLUMNS") {
    raw->names = values;
  } else if (key == "SIZE") {
    raw->sizes = values;
  } else if (key == "TYPE") {
    raw->types = values;
  } else if (key == "COUNT") {
    raw->counts = values;
  } else if (key == "WIDTH") {
    header->width = single();
    raw->has_width = true;
  } else if (key == "HEIGHT") {
    header->height = single();
  } else if (key == "POINTS") {
    header->points = single();
    raw->has_points = true;
  } else {
    ThrowFileError(path, "malformed header: unknown line '" + key + "'");
  }
}

void BuildFields(const std::string& path, const RawHeader& raw, PcdHeader* header) {
  const std::size_t n = raw.names.size();
  if (n == 0) ThrowFileError(path, "malformed header: no FIELDS line");
  if (raw.sizes.size() != n || raw.types.size() != n ||
      (!raw.counts.empty() && raw.counts.size() != n)) {
    ThrowFileError(path, "malformed header: FIELDS, SIZE, TYPE and COUNT disagree in length");
  }
  bool seen[internal::kNumSlots] = {};
  for (std::size_t i = 0; i < n; ++i) {
    PcdField f;
    f.name = raw.names[i];
    f.type = ParseType(path, raw.types[i], ParseCount(path, "SIZE", raw.sizes[i]));
    f.count = raw.counts.empty() ? 1 : ParseCount(path, "COUNT", raw.counts[i]);
    if (f.count == 0) ThrowFileError(path, "malformed header: field " + f.name + " has COUNT 0");
    // A point record must have a size that size_t holds (a wrapped one would read garbage).
    const std::size_t room = std::numeric_limits<std::size_t>::max() - header->point_step;
    if (f.count > room / static_cast<std::size_t>(f.type.size)) {
      ThrowFileError(path, "malformed header: field " + f.name + " has COUNT " +
                               std::to_string(f.count) + ", more bytes than a point can hold");
    }
    f.offset = header->point_step;
    header->point_step += header->FieldBytes(f);
    const int slot = internal::SlotForName(f.name);
    // A multi-valued field (a histogram, say) is not a scalar attribute: read past it.
    if (slot != internal::kNone && f.count == 1 && !seen[slot]) {
      f.slot = slot;
      seen[slot] = true;
    }
    header->fields.push_back(f);
  }
}

PcdHeader ReadHeader(const std::string& path, std::ifstream* in) {
  constexpr int kMaxHeaderLines = 1000;
  PcdHeader header;
  RawHeader raw;
  std::string line;
  for (int line_no = 0; line_no < kMaxHeaderLines && std::getline(*in, line); ++line_no) {
    const std::vector<std::string> words = internal::SplitWords(line);
    if (words.empty() || words[0][0] == '#') continue;
    if (words[0] != "DATA") {
      ApplyHeaderLine(path, words, &raw, &header);
      continue;
    }
    header.data = words.size() == 2 ? words[1] : "";
    if (header.data != "ascii" && header.data != "binary" && header.data != "binary_compressed") {
      ThrowFileError(path, "malformed header: unknown DATA '" + line + "'");
    }
    if (!raw.has_width) ThrowFileError(path, "malformed header: no WIDTH line");
    if (header.height != 0 &&
        header.width > std::numeric_limits<std::size_t>::max() / header.height) {
      ThrowFileError(path, "malformed header: WIDTH * HEIGHT overflows");
    }
    if (!raw.has_points) header.points = header.width * header.height;
    if (header.points != header.width * header.height) {
      ThrowFileError(
          path, "malformed header: POINTS " + std::to_string(header.points) + " != WIDTH * HEIGHT");
    }
    BuildFields(path, raw, &header);
    return header;
  }
  ThrowFileError(path, "malformed header: no DATA line (not a PCD file?)");
}

void Truncated(const std::string& path, std::size_t have, const std::string& promise) {
  ThrowFileError(path,
                 "truncated: " + std::to_string(have) + " data bytes, header promises " + promise);
}

std::string PointsOf(const PcdHeader& header) {
  return std::to_string(header.points) + " points of " + std::to_string(header.point_step) +
         " bytes";
}

// Decodes records where field f of point i starts at base + i * stride[f] + start[f].
CloudFile DecodeBinary(const std::string& path, const PcdHeader& header, const uint8_t* base,
                       const std::vector<std::size_t>& start,
                       const std::vector<std::size_t>& stride) {
  bool present[internal::kNumSlots] = {};
  for (const PcdField& f : header.fields) {
    if (f.slot != internal::kNone) present[f.slot] = true;
  }
  internal::CloudBuilder builder(path, present, header.points);
  double record[internal::kNumSlots] = {};
  for (std::size_t i = 0; i < header.points; ++i) {
    for (std::size_t k = 0; k < header.fields.size(); ++k) {
      const PcdField& f = header.fields[k];
      if (f.slot == internal::kNone) continue;
      record[f.slot] = internal::DecodeScalar(base + start[k] + i * stride[k], f.type, false);
    }
    builder.Add(record);
  }
  return builder.Finish();
}

CloudFile ReadBinaryBody(const std::string& path, const PcdHeader& header,
                         const std::vector<uint8_t>& body) {
  if (body.size() / header.point_step < header.points) {
    Truncated(path, body.size(), PointsOf(header));
  }
  std::vector<std::size_t> start, stride;
  for (const PcdField& f : header.fields) {
    start.push_back(f.offset);
    stride.push_back(header.point_step);
  }
  return DecodeBinary(path, header, body.data(), start, stride);
}

uint32_t ReadU32(const uint8_t* p) {
  return static_cast<uint32_t>(internal::DecodeScalar(p, {ScalarKind::kUnsigned, 4}, false));
}

CloudFile ReadCompressedBody(const std::string& path, const PcdHeader& header,
                             const std::vector<uint8_t>& body) {
  if (body.size() < 8) Truncated(path, body.size(), "an 8-byte size block");
  const uint32_t compressed_size = ReadU32(body.data());
  const uint32_t uncompressed_size = ReadU32(body.data() + 4);
  if (body.size() - 8 < compressed_size) {
    Truncated(path, body.size() - 8, std::to_string(compressed_size) + " compressed bytes");
  }
  const std::size_t expected = header.points * header.point_step;
  if (header.points > UINT32_MAX / header.point_step || uncompressed_size != expected) {
    ThrowFileError(path, "corrupt: compressed block expands to " +
                             std::to_string(uncompressed_size) + " bytes, header implies " +
                             std::to_string(expected));
  }
  const std::vector<uint8_t> raw =
      internal::LzfDecompress(path, body.data() + 8, compressed_size, expected);
  // Field-major: all values of field 0, then all of field 1, ...
  std::vector<std::size_t> start, stride;
  std::size_t offset = 0;
  for (const PcdField& f : header.fields) {
    start.push_back(offset);
    stride.push_back(header.FieldBytes(f));
    offset += header.points * header.FieldBytes(f);
  }
  return DecodeBinary(path, header, raw.data(), start, stride);
}

// One point per line; blank lines are skipped. A line with the wrong number of values is an
// error naming the line (counted from the first data line).
CloudFile ReadAsciiBody(const std::string& path, const PcdHeader& header,
                        const std::vector<uint8_t>& body) {
  bool present[internal::kNumSlots] = {};
  std::size_t values_per_point = 0;
  for (const PcdField& f : header.fields) {
    if (f.slot != internal::kNone) present[f.slot] = true;
    values_per_point += f.count;
  }
  internal::CloudBuilder builder(path, present, std::min(header.points, body.size()));
  // No point to read: the body is not looked at, nor a buffer sized from the header's counts.
  if (header.points == 0) return builder.Finish();
  // Each value takes at least one character: more per point than the body holds is a
  // truncated file, found before the per-point buffer is sized from the header's counts.
  if (values_per_point > body.size()) {
    Truncated(path, body.size(), std::to_string(values_per_point) + " ascii values per point");
  }
  const std::string text(body.begin(), body.end());
  std::vector<double> values(values_per_point);
  double record[internal::kNumSlots] = {};
  std::size_t line_start = 0, line_no = 0, points_read = 0;
  while (points_read < header.points && line_start < text.size()) {
    std::size_t line_end = text.find('\n', line_start);
    if (line_end == std::string::npos) line_end = text.size();
    const std::string line = text.substr(line_start, line_end - line_start);
    line_start = line_end + 1;
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const char* cursor = line.c_str();
    std::size_t count = 0;
    for (char* end = nullptr;; cursor = end) {
      const double value = std::strtod(cursor, &end);
      if (end == cursor) break;
      if (count < values_per_point) values[count] = value;
      ++count;
    }
    const bool junk = line.find_first_not_of(" \t\r", cursor - line.c_str()) != std::string::npos;
    if (count != values_per_point || junk) {
      ThrowFileError(path, "malformed or truncated ascii data line " + std::to_string(line_no) +
                               ": expected " + std::to_string(values_per_point) +
                               " numbers, found " + std::to_string(count) +
                               (junk ? " and text" : ""));
    }
    std::size_t v = 0;
    for (const PcdField& f : header.fields) {
      if (f.slot != internal::kNone) record[f.slot] = internal::AsDeclared(values[v], f.type);
      v += f.count;
    }
    builder.Add(record);
    ++points_read;
  }
  if (points_read < header.points) {
    ThrowFileError(path, "truncated: " + std::to_string(points_read) + " ascii points, header " +
                             "promises " + std::to_string(header.points));
  }
  return builder.Finish();
}

}  // namespace

CloudFile ReadPcd(const std::string& path) {
  std::ifstream in = internal::OpenForReading(path);
  const PcdHeader header = ReadHeader(path, &in);
  const std::vector<uint8_t> body = internal::ReadRest(&in);
  if (header.data == "ascii") return ReadAsciiBody(path, header, body);
  if (header.data == "binary") return ReadBinaryBody(path, header, body);
  return ReadCompressedBody(path, header, body);
}

CloudFileInfo ReadPcdInfo(const std::string& path) {
  std::ifstream in = internal::OpenForReading(path);
  const PcdHeader header = ReadHeader(path, &in);
  CloudFileInfo info;
  info.format = "pcd";
  info.encoding = header.data;
  info.points = header.points;
  for (const PcdField& f : header.fields) info.fields.push_back(f.name);
  return info;
}

}  // namespace hylo::io
