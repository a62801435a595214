#pragma once
// Internal to hylo::io: the LZF stream inside a PCD `binary_compressed` block, by liblzf, with
// its contract kept in one place (an empty input never reaches it; failures become errors
// naming the file).

#include <cstddef>
#include <cstdint>
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

}  // namespace hylo::io::internal
