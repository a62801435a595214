#pragma once
// LZF (Marc Lehmann's liblzf format), the compression inside PCD `binary_compressed` files.
// Written from the format description: a stream of chunks, each led by a control byte c:
//   c < 32            literal run: the next c + 1 bytes are copied as they are;
//   c >= 32           back-reference: length field L = c >> 5 (L == 7: add the next byte),
//                     offset = ((c & 31) << 8 | next byte); copies L + 2 bytes starting
//                     offset + 1 bytes before the current end of the output (may overlap).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hylo::io {

/// Compresses `size` bytes. Never fails: incompressible data grows by at most one byte per 32
/// (the literal-run control bytes).
std::vector<uint8_t> LzfCompress(const uint8_t* input, std::size_t size);

/// Decompresses `size` bytes that must expand to exactly `expected_size` bytes into `output`.
/// Returns false and says why (truncated chunk, reference before the start, size mismatch)
/// on corrupt input; never reads or writes out of bounds.
bool LzfDecompress(const uint8_t* input, std::size_t size, std::size_t expected_size,
                   std::vector<uint8_t>* output, std::string* why);

}  // namespace hylo::io
