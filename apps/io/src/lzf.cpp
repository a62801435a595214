#include "hylo/io/lzf.h"

#include <algorithm>
#include <array>

namespace hylo::io {
namespace {

constexpr std::size_t kMaxLiteralRun = 32;      // control byte 0..31 = run of 1..32
constexpr std::size_t kMinMatch = 3;            // length field 1 = 3 bytes
constexpr std::size_t kMaxMatch = 7 + 255 + 2;  // length field 7 + extension byte 255
constexpr std::size_t kMaxDistance = 1 << 13;   // 13 offset bits, offset = distance - 1
constexpr int kHashBits = 14;

uint32_t Hash3(const uint8_t* p) {
  const uint32_t v = (uint32_t{p[0]} << 16) | (uint32_t{p[1]} << 8) | p[2];
  // Multiplicative hashing (Knuth): the top bits of v * golden ratio spread nearby values.
  return (v * 2654435761u) >> (32 - kHashBits);
}

class LzfWriter {
 public:
  LzfWriter(const uint8_t* input, std::size_t size) : input_(input) {
    out_.reserve(size + size / kMaxLiteralRun + 2);
  }

  void Literal(std::size_t pos) {
    if (literal_count_ == 0) literal_start_ = pos;
    if (++literal_count_ == kMaxLiteralRun) FlushLiterals();
  }

  void Match(std::size_t distance, std::size_t length) {
    FlushLiterals();
    const std::size_t offset = distance - 1;
    const std::size_t length_field = length - 2;
    const auto high = static_cast<uint8_t>(offset >> 8);
    if (length_field < 7) {
      out_.push_back(static_cast<uint8_t>((length_field << 5) | high));
    } else {
      out_.push_back(static_cast<uint8_t>((7 << 5) | high));
      out_.push_back(static_cast<uint8_t>(length_field - 7));
    }
    out_.push_back(static_cast<uint8_t>(offset & 0xff));
  }

  std::vector<uint8_t> Finish() {
    FlushLiterals();
    return std::move(out_);
  }

 private:
  void FlushLiterals() {
    if (literal_count_ == 0) return;
    out_.push_back(static_cast<uint8_t>(literal_count_ - 1));
    out_.insert(out_.end(), input_ + literal_start_, input_ + literal_start_ + literal_count_);
    literal_count_ = 0;
  }

  const uint8_t* input_;
  std::vector<uint8_t> out_;
  std::size_t literal_start_ = 0;
  std::size_t literal_count_ = 0;
};

}  // namespace

std::vector<uint8_t> LzfCompress(const uint8_t* input, std::size_t size) {
  // Greedy LZ77: the last position of each 3-byte hash is the only candidate.
  std::vector<int64_t> last_seen(std::size_t{1} << kHashBits, -1);
  LzfWriter writer(input, size);
  std::size_t pos = 0;
  while (pos + kMinMatch <= size) {
    const uint32_t h = Hash3(input + pos);
    const int64_t candidate = last_seen[h];
    last_seen[h] = static_cast<int64_t>(pos);
    const bool usable = candidate >= 0 && pos - candidate <= kMaxDistance &&
                        std::equal(input + pos, input + pos + kMinMatch, input + candidate);
    if (!usable) {
      writer.Literal(pos++);
      continue;
    }
    const std::size_t limit = std::min(kMaxMatch, size - pos);
    std::size_t length = kMinMatch;
    while (length < limit && input[candidate + length] == input[pos + length]) ++length;
    writer.Match(pos - candidate, length);
    // Index the positions inside the match too, so later repeats find the nearest copy.
    for (std::size_t k = pos + 1; k < pos + length && k + kMinMatch <= size; ++k) {
      last_seen[Hash3(input + k)] = static_cast<int64_t>(k);
    }
    pos += length;
  }
  while (pos < size) writer.Literal(pos++);
  return writer.Finish();
}

bool LzfDecompress(const uint8_t* input, std::size_t size, std::size_t expected_size,
                   std::vector<uint8_t>* output, std::string* why) {
  auto fail = [why](const std::string& reason) {
    if (why != nullptr) *why = reason;
    return false;
  };
  output->assign(expected_size, 0);
  uint8_t* out = output->data();
  std::size_t in_pos = 0;
  std::size_t out_pos = 0;
  while (in_pos < size) {
    const std::size_t ctrl = input[in_pos++];
    if (ctrl < 32) {
      const std::size_t run = ctrl + 1;
      if (in_pos + run > size) return fail("LZF literal run past the end of the input");
      if (out_pos + run > expected_size) return fail("LZF output longer than announced");
      std::copy(input + in_pos, input + in_pos + run, out + out_pos);
      in_pos += run;
      out_pos += run;
      continue;
    }
    std::size_t length = ctrl >> 5;
    if (length == 7) {
      if (in_pos >= size) return fail("LZF back-reference cut off");
      length += input[in_pos++];
    }
    if (in_pos >= size) return fail("LZF back-reference cut off");
    const std::size_t distance = ((ctrl & 0x1f) << 8) + input[in_pos++] + 1;
    length += 2;
    if (distance > out_pos) return fail("LZF back-reference before the start of the output");
    if (out_pos + length > expected_size) return fail("LZF output longer than announced");
    // Byte by byte on purpose: a reference may overlap the bytes it produces (runs).
    for (std::size_t k = 0; k < length; ++k, ++out_pos) out[out_pos] = out[out_pos - distance];
  }
  if (out_pos != expected_size) {
    return fail("LZF data expands to " + std::to_string(out_pos) + " bytes, " +
                std::to_string(expected_size) + " announced");
  }
  return true;
}

}  // namespace hylo::io
