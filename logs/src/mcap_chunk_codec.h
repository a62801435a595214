#pragma once
// Private to hylo_logs: an MCAP chunk's records compressed and decompressed: "" (stored as they
// are), "zstd" (a zstd frame, libzstd) or "lz4" (an LZ4 frame, liblz4), including chunks cut
// by the end of a file.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hylo::logs::detail {

/// Decompresses `n` bytes of records compressed with `compression` into `out`. `size` is the
/// chunk's announced uncompressed size: it caps the output (at one byte more, so that data
/// longer than announced shows) but never sizes an allocation by itself. With `complete` false
/// the records stop short: whatever the codec decodes from the bytes there are is returned.
/// Returns false with `*why` for an unknown codec, corrupt data, or (complete data) a stream
/// that ends early or decodes to another size than announced.
bool DecompressMcapChunk(const std::string& compression, const uint8_t* in, std::size_t n,
                         uint64_t size, bool complete, std::vector<uint8_t>* out, std::string* why);

/// Compresses `n` bytes with "zstd" or "lz4" into `out` (replacing its content); "" copies them.
void CompressMcapChunk(const std::string& compression, const uint8_t* in, std::size_t n,
                       std::vector<uint8_t>* out);

}  // namespace hylo::logs::detail
