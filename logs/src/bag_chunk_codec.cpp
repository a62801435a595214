#include "bag_chunk_codec.h"

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <algorithm>
#include <cstring>

namespace hylo::logs::detail {
namespace {

// No chunk rosbag writes comes near this (uint32 sizes; chunks close at ~768 kB plus one
// message): a larger output is corrupt data, not a chunk.
constexpr std::size_t kMaxChunkBytes = std::size_t{1} << 31;
// The largest block an LZ4 frame (and so roslz4) can declare: 4 MiB.
constexpr std::size_t kMaxBlockBytes = std::size_t{4} << 20;

/// Room for more output, doubling; false past the limits. The announced size only caps it (at
/// one byte more, so that data longer than announced shows): a corrupt chunk header announces
/// gigabytes for a few bytes of data, so the first room is what the input may plausibly give.
bool Grow(std::size_t produced, uint32_t size, std::size_t n, std::vector<uint8_t>* out) {
  if (size > 0 && produced > size) return false;
  std::size_t want = out->empty() ? 64 * n + 4096 : 2 * out->size();
  if (size > 0) want = std::min(want, std::size_t{size} + 1);
  if (want > kMaxChunkBytes) return false;
  out->resize(want);
  return true;
}

/// What one call of a streaming decoder did.
enum class Step { kEnd, kOutputFull, kInputDone, kError };

/// Runs `decode(out, room, &produced, &code)` into `out` until the stream ends, the data is
/// corrupt or the input runs out. A cut chunk (`complete` false) keeps what came out before.
template <class Decode>
bool Drain(const std::string& codec, uint32_t size, std::size_t n, bool complete,
           std::vector<uint8_t>* out, std::string* why, Decode decode) {
  std::size_t produced = 0;
  bool ok = true;
  while (true) {
    if (produced == out->size() && !Grow(produced, size, n, out)) {
      *why = codec + ": more data than the chunk announced";
      ok = false;
      break;
    }
    int code = 0;
    const std::size_t before = produced;
    const Step step = decode(out->data() + produced, out->size() - produced, &produced, &code);
    if (step == Step::kEnd) break;
    if (step == Step::kOutputFull) {
      if (produced > before || produced == out->size()) continue;
      // Output room left and nothing written: roslz4 decodes a block only into room for the
      // stream's largest block, and asks for more room while it cannot tell that from corrupt
      // data. Give it that room once; asking again with it is corrupt data, not a full output.
      if (out->size() - produced >= kMaxBlockBytes || produced + kMaxBlockBytes > kMaxChunkBytes) {
        *why = codec + ": corrupt data (the decoder makes no progress)";
        ok = false;
        break;
      }
      out->resize(produced + kMaxBlockBytes);
      continue;
    }
    if (step == Step::kError) {
      *why = codec + ": corrupt data (code " + std::to_string(code) + ")";
    } else if (complete) {
      *why = codec + ": the chunk ends before its compressed stream";
    }
    ok = !complete;
    break;
  }
  out->resize(produced);
  return ok;
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
  const bool ok = Drain("bz2", size, n, complete, out, why,
                        [&](uint8_t* next, std::size_t room, std::size_t* produced, int* code) {
                          s.next_out = reinterpret_cast<char*>(next);
                          s.avail_out = static_cast<unsigned int>(room);
                          *code = BZ2_bzDecompress(&s);
                          *produced += room - s.avail_out;
                          if (*code == BZ_STREAM_END) return Step::kEnd;
                          if (*code != BZ_OK) return Step::kError;
                          if (s.avail_out == 0) return Step::kOutputFull;
                          return s.avail_in == 0 ? Step::kInputDone : Step::kOutputFull;
                        });
  BZ2_bzDecompressEnd(&s);
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
  const bool ok = Drain("lz4", size, n, complete, out, why,
                        [&](uint8_t* next, std::size_t room, std::size_t* produced, int* code) {
                          s.output_next = reinterpret_cast<char*>(next);
                          s.output_left = static_cast<int>(room);
                          *code = roslz4_decompress(&s);
                          *produced += room - static_cast<std::size_t>(s.output_left);
                          if (*code == ROSLZ4_STREAM_END) return Step::kEnd;
                          if (*code == ROSLZ4_OUTPUT_SMALL || s.output_left == 0) {
                            return Step::kOutputFull;
                          }
                          if (*code != ROSLZ4_OK) return Step::kError;
                          return s.input_left == 0 ? Step::kInputDone : Step::kOutputFull;
                        });
  roslz4_decompressEnd(&s);
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

}  // namespace hylo::logs::detail
