#include "pcd_lzf.h"

#include <lzf.h>

#include <algorithm>
#include <cerrno>
#include <climits>

#include "cloud_fields.h"

namespace hylo::io::internal {

std::vector<uint8_t> LzfCompress(const std::string& path, const std::vector<uint8_t>& raw) {
  if (raw.empty()) return {};  // lzf_compress returns 0, its failure value, for no input
  if (raw.size() > UINT_MAX) ThrowFileError(path, "too large for binary_compressed");
  // LZF grows data by at most one control byte per 32 literals; the slack covers liblzf's
  // conservative end-of-buffer checks, after which it gives up (returns 0).
  const auto capacity =
      static_cast<unsigned int>(std::min<std::size_t>(raw.size() + raw.size() / 32 + 64, UINT_MAX));
  std::vector<uint8_t> packed(capacity);
  const unsigned int size =
      lzf_compress(raw.data(), static_cast<unsigned int>(raw.size()), packed.data(), capacity);
  if (size == 0) ThrowFileError(path, "LZF compression failed");
  packed.resize(size);
  return packed;
}

std::vector<uint8_t> LzfDecompress(const std::string& path, const uint8_t* input, std::size_t size,
                                   std::size_t expected) {
  // The most an LZF byte can expand to: a 3-byte back reference copies at most 264 bytes.
  // Checked before the output is allocated, so a corrupt header cannot ask for gigabytes.
  constexpr std::size_t kMaxExpansion = 88;
  if (expected / kMaxExpansion > size) {
    ThrowFileError(path, "corrupt compressed data: " + std::to_string(size) +
                             " LZF bytes cannot expand to the " + std::to_string(expected) +
                             " bytes the header announces");
  }
  std::vector<uint8_t> out(expected);
  if (size == 0 && expected == 0) return out;
  if (size > UINT_MAX || expected > UINT_MAX) ThrowFileError(path, "too large for LZF");
  // lzf_decompress reads a control byte before it compares positions with the input's end, so
  // an empty stream must not reach it. On corrupt data it returns 0 and sets errno: EINVAL for
  // a stream cut short or a reference before the start of the output, E2BIG for output that
  // would run past `expected`.
  errno = 0;
  const unsigned int got = size == 0 || expected == 0
                               ? 0
                               : lzf_decompress(input, static_cast<unsigned int>(size), out.data(),
                                                static_cast<unsigned int>(expected));
  if (got == expected) return out;
  const std::string announced = std::to_string(expected) + " bytes the header announces";
  if (got == 0 && size > 0 && errno == EINVAL) {
    ThrowFileError(path,
                   "corrupt compressed data: LZF stream cut short or referring before "
                   "its start");
  }
  if (got == 0 && size > 0) {
    ThrowFileError(path, "corrupt compressed data: LZF data expands past the " + announced);
  }
  ThrowFileError(path, "corrupt compressed data: LZF data expands to " + std::to_string(got) +
                           " of the " + announced);
}

// The LZF format (liblzf's lzf_d.c documents it): a control byte c < 32 starts a literal run
// of c + 1 bytes; otherwise the top 3 bits are a length (7: plus the next byte) and a back
// reference copies length + 2 bytes from ((c & 31) << 8) + next byte + 1 bytes back, byte by
// byte (a reference may overlap what it produces).
LzfCursor::LzfCursor(const std::string& path, std::streamoff offset, std::size_t size,
                     std::size_t expected)
    : path_(path),
      in_(OpenForReading(path)),
      input_(std::size_t{1} << 16),
      input_left_(size),
      expected_(expected),
      history_(kHistory) {
  in_.seekg(offset);
}

void LzfCursor::Corrupt(const std::string& why) const {
  ThrowFileError(path_, "corrupt compressed data: " + why);
}

uint8_t LzfCursor::NextInput() {
  if (input_begin_ == input_end_) {
    const std::size_t want = std::min(input_.size(), input_left_);
    if (want == 0) Corrupt("LZF stream cut short or referring before its start");
    in_.read(reinterpret_cast<char*>(input_.data()), static_cast<std::streamsize>(want));
    const auto got = static_cast<std::size_t>(in_.gcount());
    if (got == 0) ThrowFileError(path_, "truncated: the LZF block ends before its announced size");
    input_begin_ = 0;
    input_end_ = got;
    input_left_ -= got;
  }
  return input_[input_begin_++];
}

void LzfCursor::Read(uint8_t* out, std::size_t n) {
  constexpr std::size_t kMask = kHistory - 1;
  static_assert((kHistory & kMask) == 0, "the history is a power-of-two ring");
  for (std::size_t k = 0; k < n; ++k) {
    while (literal_left_ == 0 && copy_left_ == 0) {
      const unsigned control = NextInput();
      if (control < 32) {
        literal_left_ = control + 1;
        continue;
      }
      std::size_t length = control >> 5;
      if (length == 7) length += NextInput();
      copy_distance_ = ((control & 31u) << 8) + NextInput() + 1;
      if (copy_distance_ > produced_) Corrupt("LZF stream cut short or referring before its start");
      copy_left_ = length + 2;
    }
    uint8_t byte;
    if (literal_left_ > 0) {
      byte = NextInput();
      --literal_left_;
    } else {
      byte = history_[(produced_ - copy_distance_) & kMask];
      --copy_left_;
    }
    if (produced_ == expected_) {
      Corrupt("LZF data expands past the " + std::to_string(expected_) +
              " bytes the header announces");
    }
    history_[produced_ & kMask] = byte;
    ++produced_;
    if (out != nullptr) out[k] = byte;
  }
}

}  // namespace hylo::io::internal
