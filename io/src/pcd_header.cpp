// PCD v0.7 header (pcd_format.h). The grammar follows the PCL file format description
// (pointclouds.org, "The PCD (Point Cloud Data) file format").

#include <charconv>
#include <limits>

#include "pcd_format.h"

namespace hylo::io::internal {
namespace {

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
  bool seen[kNumSlots] = {};
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
    const int slot = SlotForName(f.name);
    // A multi-valued field (a histogram, say) is not a scalar attribute: read past it.
    if (slot != kNone && f.count == 1 && !seen[slot]) {
      f.slot = slot;
      seen[slot] = true;
    }
    header->fields.push_back(f);
  }
}

}  // namespace

PcdHeader ReadPcdHeader(const std::string& path, std::ifstream* in) {
  constexpr int kMaxHeaderLines = 1000;
  PcdHeader header;
  RawHeader raw;
  std::string line;
  for (int line_no = 0; line_no < kMaxHeaderLines && std::getline(*in, line); ++line_no) {
    const std::vector<std::string> words = SplitWords(line);
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

}  // namespace hylo::io::internal
