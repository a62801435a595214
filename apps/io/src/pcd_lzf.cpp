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

}  // namespace hylo::io::internal
