// SPDX-License-Identifier: BSD-3-Clause
#include "quad/bag/crc32.hpp"

#include <array>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace quad::bag {

namespace {

/// Tables for slicing by 8: t[0] is the classic byte table; t[k][b] is the CRC of byte b
/// followed by k zero bytes.
using CrcTables = std::array<std::array<std::uint32_t, 256>, 8>;

const CrcTables& crcTables()
{
  static const auto tables = [] {
    CrcTables t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) {
        c = (c & 1U) != 0 ? 0xEDB88320U ^ (c >> 1U) : c >> 1U;
      }
      t[0][i] = c;
    }
    for (std::size_t k = 1; k < t.size(); ++k) {
      for (std::size_t i = 0; i < 256; ++i) {
        t[k][i] = (t[k - 1][i] >> 8U) ^ t[0][t[k - 1][i] & 0xFFU];
      }
    }
    return t;
  }();
  return tables;
}

/// The register form (not inverted on entry or exit), eight bytes a step.
std::uint32_t sliced(std::uint32_t crc, const std::uint8_t* p, std::size_t size)
{
  const auto& t = crcTables();
  const auto at = [&](std::size_t i) { return static_cast<std::uint32_t>(p[i]); };
  for (; size >= 8; size -= 8, p += 8) {
    const std::uint32_t lo = crc ^ (at(0) | at(1) << 8U | at(2) << 16U | at(3) << 24U);
    const std::uint32_t hi = at(4) | at(5) << 8U | at(6) << 16U | at(7) << 24U;
    crc = t[7][lo & 0xFFU] ^ t[6][(lo >> 8U) & 0xFFU] ^ t[5][(lo >> 16U) & 0xFFU] ^ t[4][lo >> 24U] ^
          t[3][hi & 0xFFU] ^ t[2][(hi >> 8U) & 0xFFU] ^ t[1][(hi >> 16U) & 0xFFU] ^ t[0][hi >> 24U];
  }
  for (; size > 0; --size, ++p) {
    crc = t[0][(crc ^ *p) & 0xFFU] ^ (crc >> 8U);
  }
  return crc;
}

#if defined(__x86_64__)
#define QUAD_CLMUL __attribute__((target("pclmul,sse4.1")))

QUAD_CLMUL __m128i load(const std::uint8_t* at) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(at)); }

/// One lane folded forward: its low half times k's low, its high half times k's high, onto
/// the data it is folded onto.
QUAD_CLMUL __m128i fold(__m128i x, __m128i k, __m128i onto)
{
  return _mm_xor_si128(_mm_xor_si128(_mm_clmulepi64_si128(x, k, 0x00), _mm_clmulepi64_si128(x, k, 0x11)), onto);
}

/// The register form over `size` bytes, a multiple of 16 and at least 64: four 128-bit lanes
/// folded forward 512 bits at a time by carry-less multiplication with x^(512±32) mod P, then
/// into one lane, to 64 bits, 32, and a Barrett reduction (Gopal et al., "Fast CRC
/// computation for generic polynomials using PCLMULQDQ", Intel 2009). The constants are
/// those powers of x modulo P, bit-reflected.
QUAD_CLMUL std::uint32_t folded(std::uint32_t crc, const std::uint8_t* p, std::size_t size)
{
  const __m128i k1k2 = _mm_set_epi64x(0x1c6e41596, 0x154442bd4);  // x^(4·128+32), x^(4·128−32)
  const __m128i k3k4 = _mm_set_epi64x(0x0ccaa009e, 0x1751997d0);  // x^(128+32), x^(128−32)
  const __m128i k5 = _mm_set_epi64x(0, 0x163cd6124);              // x^64
  const __m128i mu_p = _mm_set_epi64x(0x1f7011641, 0x1db710641);  // floor(x^64 / P), P
  const __m128i mask32 = _mm_set_epi32(0, 0, 0, -1);

  __m128i x1 = _mm_xor_si128(load(p), _mm_cvtsi32_si128(static_cast<int>(crc)));
  __m128i x2 = load(p + 16);
  __m128i x3 = load(p + 32);
  __m128i x4 = load(p + 48);
  p += 64;
  size -= 64;
  for (; size >= 64; size -= 64, p += 64) {
    x1 = fold(x1, k1k2, load(p));
    x2 = fold(x2, k1k2, load(p + 16));
    x3 = fold(x3, k1k2, load(p + 32));
    x4 = fold(x4, k1k2, load(p + 48));
  }
  x1 = fold(x1, k3k4, x2);
  x1 = fold(x1, k3k4, x3);
  x1 = fold(x1, k3k4, x4);
  for (; size >= 16; size -= 16, p += 16) {
    x1 = fold(x1, k3k4, load(p));
  }
  // 128 → 64 bits (appending 32 zero bits), then 64 → 32 bits.
  x1 = _mm_xor_si128(_mm_srli_si128(x1, 8), _mm_clmulepi64_si128(k3k4, x1, 0x01));
  x1 = _mm_xor_si128(_mm_srli_si128(x1, 4), _mm_clmulepi64_si128(_mm_and_si128(x1, mask32), k5, 0x00));
  // Barrett reduction to the 32-bit remainder.
  __m128i t = _mm_and_si128(_mm_clmulepi64_si128(_mm_and_si128(x1, mask32), mu_p, 0x10), mask32);
  t = _mm_clmulepi64_si128(t, mu_p, 0x00);
  return static_cast<std::uint32_t>(_mm_extract_epi32(_mm_xor_si128(x1, t), 1));
}

bool haveClmul()
{
  static const bool have = __builtin_cpu_supports("pclmul") && __builtin_cpu_supports("sse4.1");
  return have;
}
#undef QUAD_CLMUL
#endif

}  // namespace

std::uint32_t crc32Tables(const void* data, std::size_t size, std::uint32_t crc)
{
  return ~sliced(~crc, static_cast<const std::uint8_t*>(data), size);
}

std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc)
{
  const auto* p = static_cast<const std::uint8_t*>(data);
  crc = ~crc;
#if defined(__x86_64__)
  if (size >= 64 && haveClmul()) {
    const std::size_t n = size & ~std::size_t{15};
    crc = folded(crc, p, n);
    p += n;
    size -= n;
  }
#endif
  return ~sliced(crc, p, size);
}

}  // namespace quad::bag
