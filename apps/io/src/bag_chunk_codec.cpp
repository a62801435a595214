#include "bag_chunk_codec.h"

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <algorithm>
#include <cstring>

namespace hylo::io::detail {
namespace {

// No chunk rosbag writes comes near this (uint32 sizes; chunks close at ~768 kB plus one
// message): a larger output is corrupt data, not a chunk.
constexpr std::size_t kMaxChunkBytes = std::size_t{1} << 31;

/// Room for more output: the announced size (plus one byte, so that data longer than announced
/// shows), or doubling when the size is unknown; false past either limit.
bool Grow(std::size_t produced, uint32_t size, std::size_t n, std::vector<uint8_t>* out) {
  if (size > 0 && produced > size) return false;
  std::size_t want = 2 * out->size();
  if (out->empty()) want = size > 0 ? std::size_t{size} + 1 : 4 * n + 4096;
  if (want > kMaxChunkBytes) return false;
  out->resize(want);
  return true;
}

bool Bz2(const uint8_t* in, std::size_t n, uint32_t size, bool complete, std::vector<uint8_t>* out,
         std::string* why) {
  bz_stream s;
  std::memset(&s, 0, sizeof(s));
  if (BZ2_bzDecompressInit(&s, 0, 0) != BZ_OK) {
    *why = "bz2: cannot start the decoder";
    return false;
  }
  s.next_in = const_cast<char*>(reinterpret_cast<const char*>(in));
  s.avail_in = static_cast<unsigned int>(n);
  std::size_t produced = 0;
  bool ok = true;
  while (true) {
    if (produced == out->size() && !Grow(produced, size, n, out)) {
      *why = "bz2: more data than the chunk announced";
      ok = false;
      break;
    }
    s.next_out = reinterpret_cast<char*>(out->data() + produced);
    s.avail_out = static_cast<unsigned int>(out->size() - produced);
    const int rc = BZ2_bzDecompress(&s);
    produced = out->size() - s.avail_out;
    if (rc == BZ_STREAM_END) break;
    if (rc != BZ_OK) {
      *why = "bz2: corrupt data (code " + std::to_string(rc) + ")";
      ok = !complete;  // a cut chunk keeps what came out before the damage
      break;
    }
    if (s.avail_in == 0 && s.avail_out > 0) {  // the input ran out before the stream's end
      if (complete) *why = "bz2: the chunk ends before its compressed stream";
      ok = !complete;
      break;
    }
  }
  BZ2_bzDecompressEnd(&s);
  out->resize(produced);
  return ok;
}

bool Lz4(const uint8_t* in, std::size_t n, uint32_t size, bool complete, std::vector<uint8_t>* out,
         std::string* why) {
  roslz4_stream s;
  std::memset(&s, 0, sizeof(s));
  if (roslz4_decompressStart(&s) != ROSLZ4_OK) {
    *why = "lz4: cannot start the decoder";
    return false;
  }
  s.input_next = const_cast<char*>(reinterpret_cast<const char*>(in));
  s.input_left = static_cast<int>(n);
  std::size_t produced = 0;
  bool ok = true;
  while (true) {
    if (produced == out->size() && !Grow(produced, size, n, out)) {
      *why = "lz4: more data than the chunk announced";
      ok = false;
      break;
    }
    s.output_next = reinterpret_cast<char*>(out->data() + produced);
    s.output_left = static_cast<int>(out->size() - produced);
    const int rc = roslz4_decompress(&s);
    produced = out->size() - static_cast<std::size_t>(s.output_left);
    if (rc == ROSLZ4_STREAM_END) break;
    if (rc == ROSLZ4_OUTPUT_SMALL || (rc == ROSLZ4_OK && s.output_left == 0)) continue;
    if (rc != ROSLZ4_OK) {
      *why = "lz4: corrupt data (code " + std::to_string(rc) + ")";
      ok = !complete;
      break;
    }
    if (s.input_left == 0) {
      if (complete) *why = "lz4: the chunk ends before its compressed stream";
      ok = !complete;
      break;
    }
  }
  roslz4_decompressEnd(&s);
  out->resize(produced);
  return ok;
}

}  // namespace

bool DecompressChunk(const std::string& compression, const uint8_t* in, std::size_t n,
                     uint32_t size, bool complete, std::vector<uint8_t>* out, std::string* why) {
  out->clear();
  if (compression == "none") {
    out->assign(in, in + n);
    return true;
  }
  if (n > kMaxChunkBytes) {
    *why = compression + ": chunk too large";
    return false;
  }
  if (compression == "bz2") return Bz2(in, n, size, complete, out, why);
  if (compression == "lz4") return Lz4(in, n, size, complete, out, why);
  *why = "unknown chunk compression '" + compression + "'";
  return false;
}

}  // namespace hylo::io::detail
