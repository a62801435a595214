#pragma once
// Internal to hylo::io: pieces shared by the PCD, PLY and KITTI readers and writers.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "hylo/io/cloud_io.h"
#include "hylo/io/text.h"

namespace hylo::io::internal {

/// Opens for binary reading; throws naming the file when it is missing or unreadable.
std::ifstream OpenForReading(const std::string& path);
/// Everything from the current position to the end of the stream.
std::vector<uint8_t> ReadRest(std::ifstream* in);
/// Bytes from the current position to the end of the stream (nothing is read).
std::size_t BytesLeft(std::ifstream* in);

/// Sequential reads of a file body through a fixed buffer, so a body of any size is read in
/// O(buffer) memory.
class BufferedReader {
 public:
  explicit BufferedReader(std::ifstream* in, std::size_t buffer_bytes = std::size_t{1} << 16);
  /// The next `n` bytes into `out`; false when the file ends first (what there was is consumed).
  bool Read(uint8_t* out, std::size_t n);
  /// The next blank-separated word (spaces, tabs, line ends); false at the end of the file.
  bool NextWord(std::string* word);
  /// The next line without its line end; false at the end of the file.
  bool NextLine(std::string* line);

 private:
  bool Fill();  // false when nothing is left
  std::ifstream* in_;
  std::vector<uint8_t> buffer_;
  std::size_t begin_ = 0, end_ = 0;
};

enum class ScalarKind { kFloat, kSigned, kUnsigned };
struct ScalarType {
  ScalarKind kind = ScalarKind::kFloat;
  int size = 4;  ///< bytes: 1, 2, 4 or 8 (floats: 4 or 8)
};
/// Decodes one little-endian scalar (or big-endian when `swap` is true) as double.
double DecodeScalar(const uint8_t* bytes, ScalarType type, bool swap);

/// A number parsed from text, rounded to what a binary field of `type` would hold (text
/// "0.1" in a float32 field is the float nearest 0.1, as the writer meant).
inline double AsDeclared(double value, ScalarType type) {
  const bool is_float32 = type.kind == ScalarKind::kFloat && type.size == 4;
  return is_float32 ? static_cast<double>(static_cast<float>(value)) : value;
}

/// Label from a decoded number (uint32 values wrap to int32; non-finite -> -1).
int32_t ToLabel(double value);

/// What a named field means to CloudFile; kNone fields are read past and ignored.
enum Slot { kX, kY, kZ, kIntensity, kNx, kNy, kNz, kLabel, kNumSlots, kNone = -1 };
/// x y z; intensity or scalar_intensity; normal_x or nx (y, z alike); label or scalar_label.
/// Case-insensitive.
int SlotForName(const std::string& name);

/// Collects decoded points: drops those with a non-finite coordinate (counted) and keeps
/// the attribute vectors that the file has in step with the positions.
class CloudBuilder {
 public:
  /// `present[s]` tells whether slot s exists in the file; throws if x, y or z is missing.
  CloudBuilder(const std::string& path, const bool present[kNumSlots], std::size_t reserve);
  void Add(const double record[kNumSlots]);
  CloudFile Finish() { return std::move(cloud_); }

 private:
  bool intensity_, normals_, labels_;
  CloudFile cloud_;
};

/// Throws naming the file when an attribute vector is neither empty nor positions-sized.
void CheckAttributeSizes(const std::string& path, const CloudFile& cloud);
/// True when some coordinate is beyond +-1e4 m and not exactly a float (see WriteCloud).
bool NeedsDoublePositions(const CloudFile& cloud);

/// Shortest text that reads back to the same value.
std::string FormatShortest(double value);
std::string FormatShortest(float value);

/// Writes the bytes of `value` (host order: little-endian on every supported platform).
template <typename T>
void AppendBytes(std::vector<uint8_t>* out, T value) {
  const std::size_t at = out->size();
  out->resize(at + sizeof(T));
  std::memcpy(out->data() + at, &value, sizeof(T));
}

/// Writes `text` then `body` to `path`, throwing naming the file on failure.
void WriteFileOrThrow(const std::string& path, const std::string& text,
                      const std::vector<uint8_t>& body);

}  // namespace hylo::io::internal
