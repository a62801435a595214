#pragma once
// Internal to hylo::io: the LZF stream inside a PCD `binary_compressed` block, by liblzf, with
// its contract kept in one place (an empty input never reaches it; failures become errors
// naming the file).

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace hylo::io::internal {

/// The LZF stream of `raw` (at most 4 GiB; an empty input gives an empty stream). Throws
/// naming `path` if liblzf fails.
std::vector<uint8_t> LzfCompress(const std::string& path, const std::vector<uint8_t>& raw);

/// Decompresses `size` bytes that must expand to exactly `expected` bytes. Corrupt input
/// (cut short, a reference before the start, longer or shorter than `expected`) throws
/// std::runtime_error naming `path` and the reason; nothing is read or written out of bounds.
std::vector<uint8_t> LzfDecompress(const std::string& path, const uint8_t* input, std::size_t size,
                                   std::size_t expected);

/// The same stream decoded front to back in pieces, reading the file through a small buffer:
/// LZF refers back at most 8 KiB, so an 8 KiB history is all the state it needs (a PCD
/// binary_compressed block of any size is read field by field in O(1) memory, cloud_stream.h).
/// The same corrupt input as LzfDecompress throws the same kind of error naming `path`.
class LzfCursor {
 public:
  /// The stream is `size` bytes at byte `offset` of `path` and expands to `expected` bytes.
  LzfCursor(const std::string& path, std::streamoff offset, std::size_t size, std::size_t expected);
  /// The next `n` decompressed bytes into `out`, or dropped when `out` is nullptr.
  void Read(uint8_t* out, std::size_t n);

 private:
  static constexpr std::size_t kHistory = 8192;  // longest back reference of LZF
  uint8_t NextInput();
  [[noreturn]] void Corrupt(const std::string& why) const;

  std::string path_;
  std::ifstream in_;
  std::vector<uint8_t> input_;
  std::size_t input_begin_ = 0, input_end_ = 0;
  std::size_t input_left_;  // stream bytes not yet buffered
  std::size_t expected_;
  std::size_t produced_ = 0;
  std::vector<uint8_t> history_;  // the last kHistory output bytes, ring
  std::size_t literal_left_ = 0;  // bytes of the current literal run still to copy
  std::size_t copy_left_ = 0;     // bytes of the current back reference still to copy
  std::size_t copy_distance_ = 0;
};

}  // namespace hylo::io::internal
