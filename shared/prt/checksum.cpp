#include "prt/checksum.h"

#include <array>
#include <cstring>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <nmmintrin.h>
#define PRT_CRC32C_SSE42 1
#endif

namespace prt {
namespace {

constexpr std::uint32_t kCrc32cPolyReflected = 0x82F63B78u;

// Slicing-by-8 tables (Intel's "slicing-by-8"): table[0] is the classic byte-at-a-time
// table; table[k][b] is the CRC of byte b followed by k zero bytes, so eight table lookups
// advance the CRC by eight bytes. Built at compile time, 8 KiB.
using Crc32cTables = std::array<std::array<std::uint32_t, 256>, 8>;

constexpr Crc32cTables makeCrc32cTables() {
  Crc32cTables t{};
  for (std::uint32_t b = 0; b < 256; ++b) {
    std::uint32_t c = b;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? (c >> 1) ^ kCrc32cPolyReflected : c >> 1;
    t[0][b] = c;
  }
  for (std::size_t k = 1; k < 8; ++k)
    for (std::size_t b = 0; b < 256; ++b) t[k][b] = (t[k - 1][b] >> 8) ^ t[0][t[k - 1][b] & 0xFFu];
  return t;
}

constexpr Crc32cTables kTables = makeCrc32cTables();

static_assert(kTables[0][1] == 0xF26B8303u, "CRC-32C table generation");

#ifdef PRT_CRC32C_SSE42
// SSE4.2's crc32 instruction computes this very CRC (same polynomial, reflected), several
// times faster than the tables: the sharded bake's files are checked at hundreds of MB a
// pass. Chosen at run time, so the build does not require the instruction.
__attribute__((target("sse4.2"))) std::uint32_t crc32cHardware(const std::uint8_t* p, std::size_t n,
                                                              std::uint32_t c) noexcept {
  std::uint64_t c64 = c;
  while (n >= 8) {
    std::uint64_t word;
    std::memcpy(&word, p, 8);  // x86 is little-endian: the bytes in the order the CRC takes them
    c64 = _mm_crc32_u64(c64, word);
    p += 8;
    n -= 8;
  }
  c = static_cast<std::uint32_t>(c64);
  while (n > 0) {
    c = _mm_crc32_u8(c, *p);
    ++p;
    --n;
  }
  return c;
}

const bool kHasSse42 = __builtin_cpu_supports("sse4.2");
#endif

}  // namespace

std::uint32_t crc32c(std::span<const std::uint8_t> bytes, std::uint32_t crc) noexcept {
#ifdef PRT_CRC32C_SSE42
  if (kHasSse42) return ~crc32cHardware(bytes.data(), bytes.size(), ~crc);
#endif
  return crc32cTables(bytes, crc);
}

std::uint32_t crc32cTables(std::span<const std::uint8_t> bytes, std::uint32_t crc) noexcept {
  std::uint32_t c = ~crc;
  const std::uint8_t* p = bytes.data();
  std::size_t n = bytes.size();
  // Bytes are assembled explicitly (not loaded as words) so the result does not depend on
  // the host's byte order or on the buffer's alignment.
  while (n >= 8) {
    const std::uint32_t lo = c ^ (static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
                                  static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24);
    const std::uint32_t hi = static_cast<std::uint32_t>(p[4]) | static_cast<std::uint32_t>(p[5]) << 8 |
                             static_cast<std::uint32_t>(p[6]) << 16 | static_cast<std::uint32_t>(p[7]) << 24;
    c = kTables[7][lo & 0xFFu] ^ kTables[6][(lo >> 8) & 0xFFu] ^ kTables[5][(lo >> 16) & 0xFFu] ^
        kTables[4][lo >> 24] ^ kTables[3][hi & 0xFFu] ^ kTables[2][(hi >> 8) & 0xFFu] ^
        kTables[1][(hi >> 16) & 0xFFu] ^ kTables[0][hi >> 24];
    p += 8;
    n -= 8;
  }
  while (n > 0) {
    c = (c >> 8) ^ kTables[0][(c ^ *p) & 0xFFu];
    ++p;
    --n;
  }
  return ~c;
}

}  // namespace prt
