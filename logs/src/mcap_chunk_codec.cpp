#include "mcap_chunk_codec.h"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "printable.h"

namespace hylo::logs::detail {
namespace {

// Chunks close at about a megabyte (rosbag2's default is 768 KiB); a chunk announcing more than
// this is corrupt data, not a recording.
constexpr uint64_t kMaxChunkBytes = uint64_t{1} << 31;

/// Room for more output: doubling from what the input may plausibly give, capped at the
/// announced size + 1 and at kMaxChunkBytes; false past them.
bool Grow(std::size_t produced, uint64_t size, std::size_t n, std::vector<uint8_t>* out) {
  if (produced > size) return false;
  uint64_t want = out->empty() ? 64 * uint64_t{n} + 4096 : 2 * uint64_t{out->size()};
  want = std::min(want, size + 1);
  if (want > kMaxChunkBytes || want <= produced) return false;
  out->resize(static_cast<std::size_t>(want));
  return true;
}

enum class Step { kEnd, kMore, kError };

/// Runs `decode(out, room, &produced)` until the stream ends, the data is corrupt or the input
/// runs out (`input_left` 0 after a step that neither ended nor filled the output).
template <class Decode, class InputLeft>
bool Drain(const std::string& codec, uint64_t size, std::size_t n, bool complete,
           std::vector<uint8_t>* out, std::string* why, Decode decode, InputLeft input_left) {
  std::size_t produced = 0;
  bool ok = true;
  while (true) {
    if (produced == out->size() && !Grow(produced, size, n, out)) {
      *why = codec + ": more data than the chunk announces";
      ok = false;
      break;
    }
    const std::size_t before = produced;
    const std::size_t left_before = input_left();
    const Step step = decode(out->data() + produced, out->size() - produced, &produced);
    if (step == Step::kError) {
      ok = false;
      break;
    }
    if (step == Step::kEnd && input_left() == 0) break;
    if (step == Step::kMore && input_left() == 0 && produced < out->size()) {
      if (complete) *why = codec + ": the chunk ends before its compressed stream";
      ok = !complete;
      break;
    }
    if (step == Step::kMore && produced == before && input_left() == left_before &&
        produced < out->size()) {
      *why = codec + ": corrupt data (the decoder makes no progress)";
      ok = false;
      break;
    }
  }
  out->resize(produced);
  if (ok && complete && produced != size) {
    *why = codec + ": " + std::to_string(produced) + " bytes, the chunk announces " +
           std::to_string(size);
    ok = false;
  }
  return ok;
}

bool Zstd(const uint8_t* in, std::size_t n, uint64_t size, bool complete, std::vector<uint8_t>* out,
          std::string* why) {
  std::unique_ptr<ZSTD_DStream, decltype(&ZSTD_freeDStream)> stream(ZSTD_createDStream(),
                                                                    &ZSTD_freeDStream);
  if (!stream || ZSTD_isError(ZSTD_initDStream(stream.get()))) {
    *why = "zstd: cannot start the decoder";
    return false;
  }
  ZSTD_inBuffer input{in, n, 0};
  return Drain(
      "zstd", size, n, complete, out, why,
      [&](uint8_t* next, std::size_t room, std::size_t* produced) {
        ZSTD_outBuffer output{next, room, 0};
        const std::size_t code = ZSTD_decompressStream(stream.get(), &output, &input);
        *produced += output.pos;
        if (ZSTD_isError(code)) {
          *why = std::string("zstd: corrupt data (") + ZSTD_getErrorName(code) + ")";
          return Step::kError;
        }
        return code == 0 ? Step::kEnd : Step::kMore;  // 0: a frame ended
      },
      [&] { return input.size - input.pos; });
}

bool Lz4(const uint8_t* in, std::size_t n, uint64_t size, bool complete, std::vector<uint8_t>* out,
         std::string* why) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    *why = "lz4: cannot start the decoder";
    return false;
  }
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(
      raw, &LZ4F_freeDecompressionContext);
  std::size_t consumed = 0;
  return Drain(
      "lz4", size, n, complete, out, why,
      [&](uint8_t* next, std::size_t room, std::size_t* produced) {
        std::size_t out_bytes = room;
        std::size_t in_bytes = n - consumed;
        const std::size_t code =
            LZ4F_decompress(context.get(), next, &out_bytes, in + consumed, &in_bytes, nullptr);
        consumed += in_bytes;
        *produced += out_bytes;
        if (LZ4F_isError(code)) {
          *why = std::string("lz4: corrupt data (") + LZ4F_getErrorName(code) + ")";
          return Step::kError;
        }
        return code == 0 ? Step::kEnd : Step::kMore;  // 0: the frame ended
      },
      [&] { return n - consumed; });
}

}  // namespace

bool DecompressMcapChunk(const std::string& compression, const uint8_t* in, std::size_t n,
                         uint64_t size, bool complete, std::vector<uint8_t>* out,
                         std::string* why) {
  out->clear();
  if (compression.empty()) {
    if (complete && n != size) {
      *why =
          "records of " + std::to_string(n) + " bytes, the chunk announces " + std::to_string(size);
      return false;
    }
    out->assign(in, in + n);
    return true;
  }
  if (size > kMaxChunkBytes) {
    *why = "a chunk announcing " + std::to_string(size) + " bytes: corrupt";
    return false;
  }
  if (compression == "zstd") return Zstd(in, n, size, complete, out, why);
  if (compression == "lz4") return Lz4(in, n, size, complete, out, why);
  *why = "unknown chunk compression '" + Printable(compression) + "'";
  return false;
}

void CompressMcapChunk(const std::string& compression, const uint8_t* in, std::size_t n,
                       std::vector<uint8_t>* out) {
  if (compression.empty()) {
    out->assign(in, in + n);
    return;
  }
  if (compression == "zstd") {
    out->resize(ZSTD_compressBound(n));
    // Level 1: what rosbag2's "fast" chunk compression uses; recording speed over size.
    const std::size_t written = ZSTD_compress(out->data(), out->size(), in, n, 1);
    if (ZSTD_isError(written)) throw std::runtime_error(ZSTD_getErrorName(written));
    out->resize(written);
    return;
  }
  if (compression == "lz4") {
    LZ4F_preferences_t preferences = LZ4F_INIT_PREFERENCES;
    preferences.frameInfo.contentSize = n;
    out->resize(LZ4F_compressFrameBound(n, &preferences));
    const std::size_t written = LZ4F_compressFrame(out->data(), out->size(), in, n, &preferences);
    if (LZ4F_isError(written)) throw std::runtime_error(LZ4F_getErrorName(written));
    out->resize(written);
    return;
  }
  throw std::invalid_argument("unknown chunk compression '" + compression + "'");
}

}  // namespace hylo::logs::detail
