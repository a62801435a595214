#pragma once
// Private to hylo_io: a bag chunk's data decompressed (bz2 through libbz2, lz4 through
// roslz4, the two codecs rosbag_storage itself links), including chunks that were cut.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hylo::logs::detail {

/// Decompresses `n` bytes of chunk data compressed with `compression` ("none", "bz2", "lz4")
/// into `out`. `size` is the chunk's uncompressed length (0 when unknown: a chunk never
/// closed). With `complete` false the data stops short: whatever the codec can decode from
/// the bytes there are is returned (lz4 gives every whole block; bz2 needs its whole 900 kB
/// block, so a cut bz2 chunk usually gives nothing). Returns false with `*why` when the codec
/// is unknown or the data is corrupt (and, for complete data, when it ends early).
bool DecompressChunk(const std::string& compression, const uint8_t* in, std::size_t n,
                     uint32_t size, bool complete, std::vector<uint8_t>* out, std::string* why);

}  // namespace hylo::logs::detail
