// CRC-32 (IEEE polynomial, reflected, as zlib and the MCAP specification compute it), which every
// MCAP chunk's records carry. Checking it runs over every byte a recording holds, so it is
// computed two ways:
//  - carry-less multiplication (PCLMULQDQ, x86-64 processors since 2010), chosen at run time:
//    the data are folded 64 bytes at a time into four 128-bit lanes, each lane multiplied by
//    x^(512 +- 32) mod P so that it moves 64 bytes on without changing its remainder (the
//    method of Intel's "Fast CRC Computation for Generic Polynomials Using PCLMULQDQ"); the
//    folded 16 bytes and the tail then go through the tables;
//  - slicing-by-8 tables everywhere else: eight look-ups per 8 bytes.

#include <cstring>

#include "mcap_format.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define HYLO_CRC32_CLMUL 1
#endif

namespace hylo::logs::detail {
namespace {

constexpr uint32_t kReflectedPolynomial = 0xEDB88320u;

struct CrcTables {
  uint32_t t[8][256];
  CrcTables() {
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? kReflectedPolynomial ^ (c >> 1) : c >> 1;
      t[0][i] = c;
    }
    for (int k = 1; k < 8; ++k) {
      for (uint32_t i = 0; i < 256; ++i) t[k][i] = (t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xff];
    }
  }
};

const CrcTables& Tables() {
  static const CrcTables tables;
  return tables;
}

// The CRC register (not inverted) after `n` more bytes.
uint32_t TableRegister(uint32_t reg, const uint8_t* p, std::size_t n) {
  const auto& t = Tables().t;
  for (; n >= 8; p += 8, n -= 8) {
    const uint32_t a = reg ^ static_cast<uint32_t>(LoadLe(p, 4));
    const uint32_t b = static_cast<uint32_t>(LoadLe(p + 4, 4));
    reg = t[7][a & 0xff] ^ t[6][(a >> 8) & 0xff] ^ t[5][(a >> 16) & 0xff] ^ t[4][a >> 24] ^
          t[3][b & 0xff] ^ t[2][(b >> 8) & 0xff] ^ t[1][(b >> 16) & 0xff] ^ t[0][b >> 24];
  }
  for (; n > 0; --n) reg = t[0][(reg ^ *p++) & 0xff] ^ (reg >> 8);
  return reg;
}

#ifdef HYLO_CRC32_CLMUL
// A lane moved on by the distance its constants encode: (low half) * k_low ^ (high half) * k_high.
__attribute__((target("pclmul,sse4.1"))) inline __m128i Fold(__m128i lane, __m128i k) {
  return _mm_xor_si128(_mm_clmulepi64_si128(lane, k, 0x00), _mm_clmulepi64_si128(lane, k, 0x11));
}

// The register after `n` (>= 64) more bytes.
__attribute__((target("pclmul,sse4.1"))) uint32_t ClmulRegister(uint32_t reg, const uint8_t* p,
                                                                 std::size_t n) {
  // x^(4*128+32) and x^(4*128-32) mod P (64 bytes on), x^(128+32) and x^(128-32) mod P
  // (16 bytes on), bit-reflected, as 33-bit values.
  const __m128i by64 = _mm_set_epi64x(0x1c6e41596, 0x154442bd4);
  const __m128i by16 = _mm_set_epi64x(0x0ccaa009e, 0x1751997d0);
  const auto load = [](const uint8_t* at) {
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(at));
  };
  // The register enters as the first four bytes' complement partner: XORing it into them and
  // starting again from 0 is the same CRC.
  __m128i x0 = _mm_xor_si128(load(p), _mm_cvtsi32_si128(static_cast<int>(reg)));
  __m128i x1 = load(p + 16);
  __m128i x2 = load(p + 32);
  __m128i x3 = load(p + 48);
  p += 64;
  n -= 64;
  for (; n >= 64; p += 64, n -= 64) {
    x0 = _mm_xor_si128(Fold(x0, by64), load(p));
    x1 = _mm_xor_si128(Fold(x1, by64), load(p + 16));
    x2 = _mm_xor_si128(Fold(x2, by64), load(p + 32));
    x3 = _mm_xor_si128(Fold(x3, by64), load(p + 48));
  }
  __m128i x = _mm_xor_si128(Fold(x0, by16), x1);
  x = _mm_xor_si128(Fold(x, by16), x2);
  x = _mm_xor_si128(Fold(x, by16), x3);
  for (; n >= 16; p += 16, n -= 16) x = _mm_xor_si128(Fold(x, by16), load(p));
  alignas(16) uint8_t folded[16];
  _mm_store_si128(reinterpret_cast<__m128i*>(folded), x);
  return TableRegister(TableRegister(0, folded, sizeof(folded)), p, n);
}

bool HasClmul() {
  static const bool has = __builtin_cpu_supports("pclmul") && __builtin_cpu_supports("sse4.1");
  return has;
}
#endif

}  // namespace

uint32_t Crc32Tables(const uint8_t* data, std::size_t n, uint32_t crc) {
  return ~TableRegister(~crc, data, n);
}

uint32_t Crc32(const uint8_t* data, std::size_t n, uint32_t crc) {
#ifdef HYLO_CRC32_CLMUL
  if (n >= 64 && HasClmul()) return ~ClmulRegister(~crc, data, n);
#endif
  return Crc32Tables(data, n, crc);
}

}  // namespace hylo::logs::detail
