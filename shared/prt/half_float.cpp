#include "prt/half_float.h"

#include <cstring>

namespace prt {
namespace {

std::uint32_t bitsOf(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

float floatOf(std::uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

// Shifts `m` right by `shift` (1..31) rounding to nearest, ties to even.
std::uint32_t shiftRoundEven(std::uint32_t m, int shift) {
  const std::uint32_t half = 1u << (shift - 1);
  const std::uint32_t rest = m & ((1u << shift) - 1u);
  std::uint32_t q = m >> shift;
  if (rest > half || (rest == half && (q & 1u))) ++q;
  return q;
}

}  // namespace

std::uint16_t floatToHalf(float value) noexcept {
  const std::uint32_t x = bitsOf(value);
  const auto sign = static_cast<std::uint16_t>((x >> 16) & 0x8000u);
  const std::uint32_t mag = x & 0x7fffffffu;
  if (mag >= 0x7f800000u) {  // infinity or NaN
    return static_cast<std::uint16_t>(sign | 0x7c00u | (mag > 0x7f800000u ? 0x0200u : 0u));
  }
  const int exponent = static_cast<int>(mag >> 23);  // biased by 127
  const std::uint32_t mantissa = (mag & 0x7fffffu) | 0x800000u;
  if (exponent < 113) {
    // Below 2^-14: a subnormal half, a multiple of 2^-24. value = mantissa * 2^(exponent-150),
    // so the multiple is mantissa >> (126 - exponent), rounded. Below 2^-25 it rounds to 0
    // (exactly 2^-25 is a tie and goes to the even 0).
    if (exponent < 102) return sign;
    return static_cast<std::uint16_t>(sign | shiftRoundEven(mantissa, 126 - exponent));
  }
  // Normal: drop 13 mantissa bits with rounding; a carry into the exponent is right (it
  // gives the next binade, or infinity past 65504).
  const std::uint32_t rounded = shiftRoundEven(mag - (112u << 23), 13);
  if (rounded >= 0x7c00u) return static_cast<std::uint16_t>(sign | 0x7c00u);
  return static_cast<std::uint16_t>(sign | rounded);
}

float halfToFloat(std::uint16_t bits) noexcept {
  const std::uint32_t sign = static_cast<std::uint32_t>(bits & 0x8000u) << 16;
  const std::uint32_t exponent = (bits >> 10) & 0x1fu;
  std::uint32_t mantissa = bits & 0x3ffu;
  if (exponent == 0x1fu) return floatOf(sign | 0x7f800000u | (mantissa << 13));
  if (exponent != 0) return floatOf(sign | ((exponent + 112u) << 23) | (mantissa << 13));
  if (mantissa == 0) return floatOf(sign);
  // Subnormal half: normalise into a float.
  int e = 113;
  while ((mantissa & 0x400u) == 0) {
    mantissa <<= 1;
    --e;
  }
  return floatOf(sign | (static_cast<std::uint32_t>(e) << 23) | ((mantissa & 0x3ffu) << 13));
}

}  // namespace prt
