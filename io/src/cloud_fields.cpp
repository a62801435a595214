#include "cloud_fields.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "hylo/io/atomic_file.h"

namespace hylo::io::internal {

static_assert(sizeof(float) == 4 && sizeof(double) == 8, "IEEE-754 float/double expected");

std::ifstream OpenForReading(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) ThrowFileError(path, "cannot open (missing or unreadable)");
  return in;
}

std::vector<uint8_t> ReadRest(std::ifstream* in) {
  std::vector<uint8_t> bytes(BytesLeft(in));
  in->read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return bytes;
}

std::size_t BytesLeft(std::ifstream* in) {
  const std::streampos start = in->tellg();
  in->seekg(0, std::ios::end);
  const std::streampos end = in->tellg();
  in->seekg(start);
  return static_cast<std::size_t>(end - start);
}

BufferedReader::BufferedReader(std::ifstream* in, std::size_t buffer_bytes)
    : in_(in), buffer_(buffer_bytes) {}

bool BufferedReader::Fill() {
  if (begin_ < end_) return true;
  in_->read(reinterpret_cast<char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size()));
  begin_ = 0;
  end_ = static_cast<std::size_t>(in_->gcount());
  return end_ > 0;
}

bool BufferedReader::Read(uint8_t* out, std::size_t n) {
  while (n > 0) {
    if (!Fill()) return false;
    const std::size_t take = std::min(n, end_ - begin_);
    std::memcpy(out, buffer_.data() + begin_, take);
    begin_ += take;
    out += take;
    n -= take;
  }
  return true;
}

bool BufferedReader::NextWord(std::string* word) {
  word->clear();
  while (Fill()) {
    const char c = static_cast<char>(buffer_[begin_]);
    const bool blank = c == ' ' || c == '\t' || c == '\n' || c == '\r';
    if (blank && !word->empty()) return true;
    if (!blank) word->push_back(c);
    ++begin_;
  }
  return !word->empty();
}

bool BufferedReader::NextLine(std::string* line) {
  line->clear();
  bool any = false;
  while (Fill()) {
    any = true;
    const uint8_t* start = buffer_.data() + begin_;
    const auto* stop = static_cast<const uint8_t*>(std::memchr(start, '\n', end_ - begin_));
    const std::size_t take =
        stop == nullptr ? end_ - begin_ : static_cast<std::size_t>(stop - start);
    line->append(reinterpret_cast<const char*>(start), take);
    begin_ += take;
    if (stop != nullptr) {
      ++begin_;  // the line end
      return true;
    }
  }
  return any;
}

namespace {
template <typename T>
double Load(const uint8_t* bytes, bool swap) {
  std::array<uint8_t, sizeof(T)> raw;
  std::memcpy(raw.data(), bytes, sizeof(T));
  if (swap) std::reverse(raw.begin(), raw.end());
  T value;
  std::memcpy(&value, raw.data(), sizeof(T));
  return static_cast<double>(value);
}
}  // namespace

int32_t ToLabel(double value) {
  // uint32 labels (PCL's type) wrap to int32, so 0xFFFFFFFF ("unlabelled") reads as -1 and
  // writes back as the same 32 bits; anything else out of range or non-finite becomes -1.
  constexpr double kTwo31 = 2147483648.0;
  if (!std::isfinite(value) || value < -kTwo31 || value >= 2 * kTwo31) return -1;
  if (value >= kTwo31) value -= 2 * kTwo31;
  return static_cast<int32_t>(value);
}

double DecodeScalar(const uint8_t* bytes, ScalarType type, bool swap) {
  switch (type.kind) {
    case ScalarKind::kFloat:
      return type.size == 4 ? Load<float>(bytes, swap) : Load<double>(bytes, swap);
    case ScalarKind::kSigned:
      switch (type.size) {
        case 1:
          return Load<int8_t>(bytes, swap);
        case 2:
          return Load<int16_t>(bytes, swap);
        case 4:
          return Load<int32_t>(bytes, swap);
        default:
          return Load<int64_t>(bytes, swap);
      }
    case ScalarKind::kUnsigned:
      switch (type.size) {
        case 1:
          return Load<uint8_t>(bytes, swap);
        case 2:
          return Load<uint16_t>(bytes, swap);
        case 4:
          return Load<uint32_t>(bytes, swap);
        default:
          return Load<uint64_t>(bytes, swap);
      }
  }
  return 0.0;
}

int SlotForName(const std::string& name) {
  const std::string n = ToLower(name);
  if (n == "x") return kX;
  if (n == "y") return kY;
  if (n == "z") return kZ;
  if (n == "intensity" || n == "scalar_intensity") return kIntensity;
  if (n == "normal_x" || n == "nx") return kNx;
  if (n == "normal_y" || n == "ny") return kNy;
  if (n == "normal_z" || n == "nz") return kNz;
  if (n == "label" || n == "scalar_label") return kLabel;
  return kNone;
}

CloudBuilder::CloudBuilder(const std::string& path, const bool present[kNumSlots],
                           std::size_t reserve)
    : intensity_(present[kIntensity]),
      normals_(present[kNx] && present[kNy] && present[kNz]),
      labels_(present[kLabel]) {
  if (!present[kX] || !present[kY] || !present[kZ]) {
    ThrowFileError(path, "no x, y and z fields");
  }
  cloud_.positions.reserve(reserve);
  if (intensity_) cloud_.intensity.reserve(reserve);
  if (normals_) cloud_.normals.reserve(reserve);
  if (labels_) cloud_.labels.reserve(reserve);
}

void CloudBuilder::Add(const double record[kNumSlots]) {
  if (!std::isfinite(record[kX]) || !std::isfinite(record[kY]) || !std::isfinite(record[kZ])) {
    ++cloud_.dropped_non_finite;
    return;
  }
  cloud_.positions.emplace_back(record[kX], record[kY], record[kZ]);
  if (intensity_) cloud_.intensity.push_back(static_cast<float>(record[kIntensity]));
  if (normals_) {
    cloud_.normals.emplace_back(static_cast<float>(record[kNx]), static_cast<float>(record[kNy]),
                                static_cast<float>(record[kNz]));
  }
  if (labels_) cloud_.labels.push_back(ToLabel(record[kLabel]));
}

void CheckAttributeSizes(const std::string& path, const CloudFile& cloud) {
  const std::size_t n = cloud.positions.size();
  auto check = [&](std::size_t size, const char* name) {
    if (size != 0 && size != n) {
      ThrowFileError(path, std::string("cannot write: ") + name + " has " + std::to_string(size) +
                               " values for " + std::to_string(n) + " positions");
    }
  };
  check(cloud.intensity.size(), "intensity");
  check(cloud.normals.size(), "normals");
  check(cloud.labels.size(), "labels");
}

bool NeedsDoublePositions(const CloudFile& cloud) {
  constexpr double kFloatSafeAbs = 1e4;  // float spacing below 1 mm up to here
  for (const Eigen::Vector3d& p : cloud.positions) {
    for (int k = 0; k < 3; ++k) {
      const double c = p[k];
      if (std::abs(c) > kFloatSafeAbs && static_cast<double>(static_cast<float>(c)) != c) {
        return true;
      }
    }
  }
  return false;
}

std::string FormatShortest(double value) {
  char buffer[40];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

std::string FormatShortest(float value) {
  char buffer[40];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

void WriteFileOrThrow(const std::string& path, const std::string& text,
                      const std::vector<uint8_t>& body) {
  WriteFileAtomically(path, text, reinterpret_cast<const char*>(body.data()), body.size());
}

}  // namespace hylo::io::internal
