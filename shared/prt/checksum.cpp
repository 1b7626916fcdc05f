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
// The hardware path runs three independent CRCs over three lanes of kLaneBytes (the crc32
// instruction's latency is three times its throughput, so one dependent chain leaves two
// thirds of it idle) and joins them: the CRC register is linear, so the register after
// A B C is shift_{|B|+|C|}(crc A) ^ shift_{|C|}(crc B from 0) ^ crc C from 0, where shift_n is
// the register after n zero bytes, a linear map of 32 bits: four 256-entry tables.
constexpr std::size_t kLaneBytes = 1024;

constexpr std::uint32_t afterZeros(std::uint32_t x, std::size_t zeros) {
  for (std::size_t i = 0; i < zeros; ++i) x = (x >> 8) ^ kTables[0][x & 0xFFu];
  return x;
}

using ShiftTable = std::array<std::array<std::uint32_t, 256>, 4>;

constexpr ShiftTable makeShiftTable(std::size_t zeros) {
  std::array<std::uint32_t, 32> basis{};
  for (std::size_t i = 0; i < 32; ++i) basis[i] = afterZeros(std::uint32_t{1} << i, zeros);
  ShiftTable t{};
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::uint32_t b = 0; b < 256; ++b) {
      std::uint32_t v = 0;
      for (std::size_t j = 0; j < 8; ++j) {
        if ((b >> j) & 1u) v ^= basis[8 * k + j];
      }
      t[k][b] = v;
    }
  }
  return t;
}

constexpr ShiftTable kShiftLane = makeShiftTable(kLaneBytes), kShiftTwoLanes = makeShiftTable(2 * kLaneBytes);

std::uint32_t shifted(const ShiftTable& t, std::uint32_t x) noexcept {
  return t[0][x & 0xFFu] ^ t[1][(x >> 8) & 0xFFu] ^ t[2][(x >> 16) & 0xFFu] ^ t[3][x >> 24];
}
#endif

#ifdef PRT_CRC32C_SSE42
// SSE4.2's crc32 instruction computes this very CRC (same polynomial, reflected), several
// times faster than the tables: the sharded bake's files are checked at hundreds of MB a
// pass. Chosen at run time, so the build does not require the instruction.
__attribute__((target("sse4.2"))) std::uint32_t crc32cHardware(const std::uint8_t* p, std::size_t n,
                                                              std::uint32_t c) noexcept {
  std::uint64_t c64 = c;
  while (n >= 3 * kLaneBytes) {
    std::uint64_t a = c64, b = 0, d = 0;
    for (std::size_t i = 0; i < kLaneBytes; i += 8) {
      std::uint64_t w0, w1, w2;
      std::memcpy(&w0, p + i, 8);
      std::memcpy(&w1, p + kLaneBytes + i, 8);
      std::memcpy(&w2, p + 2 * kLaneBytes + i, 8);
      a = _mm_crc32_u64(a, w0);
      b = _mm_crc32_u64(b, w1);
      d = _mm_crc32_u64(d, w2);
    }
    c64 = shifted(kShiftTwoLanes, static_cast<std::uint32_t>(a)) ^ shifted(kShiftLane, static_cast<std::uint32_t>(b)) ^
          static_cast<std::uint32_t>(d);
    p += 3 * kLaneBytes;
    n -= 3 * kLaneBytes;
  }
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

// Polynomials over GF(2) modulo the CRC's, bit-reflected as the CRC (bit 31 is x^0).
constexpr std::uint32_t kReflectedPolynomial = 0x82F63B78u;

// a(x) b(x) mod P(x).
std::uint32_t multiplyModP(std::uint32_t a, std::uint32_t b) noexcept {
  std::uint32_t product = 0;
  for (std::uint32_t m = 1u << 31; m != 0; m >>= 1) {
    if (a & m) product ^= b;
    b = (b & 1) ? (b >> 1) ^ kReflectedPolynomial : b >> 1;  // b(x) x
  }
  return product;
}

// x^(8 n) mod P(x): n bytes of zeros appended to a message multiply its CRC register by it.
std::uint32_t xPowerOfBytesModP(std::uint64_t n) noexcept {
  std::uint32_t power = 1u << 31;   // x^0
  std::uint32_t square = 1u << 23;  // x^8, squared for each bit of n
  for (; n != 0; n >>= 1) {
    if (n & 1) power = multiplyModP(square, power);
    square = multiplyModP(square, square);
  }
  return power;
}

}  // namespace

std::uint32_t crc32cCombine(std::uint32_t crcA, std::uint32_t crcB, std::uint64_t bBytes) noexcept {
  // The final xor of crc(a) and the initial value of b's cancel in the register algebra, as
  // in zlib: crc(a ++ b) = crc(a) x^(8 |b|) + crc(b) mod P.
  return multiplyModP(xPowerOfBytesModP(bBytes), crcA) ^ crcB;
}

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
