#include "half_float.h"

#include <cstring>

namespace prt::web {
namespace {

// Rounds `value >> shift` to nearest, ties to even (shift >= 1).
std::uint32_t shiftRoundEven(std::uint32_t value, int shift) {
  const std::uint32_t kept = value >> shift;
  const std::uint32_t rest = value & ((1u << shift) - 1u);
  const std::uint32_t half = 1u << (shift - 1);
  return kept + ((rest > half || (rest == half && (kept & 1u))) ? 1u : 0u);
}

}  // namespace

std::uint16_t floatToHalf(float value) {
  std::uint32_t f = 0;
  std::memcpy(&f, &value, sizeof f);
  const auto sign = static_cast<std::uint16_t>((f >> 16) & 0x8000u);
  f &= 0x7fffffffu;
  if (f > 0x7f800000u) return static_cast<std::uint16_t>(sign | 0x7e00u);  // NaN (quiet)
  if (f >= 0x477ff000u) return static_cast<std::uint16_t>(sign | 0x7c00u);  // >= 65520: beyond the largest half
  if (f < 0x38800000u) {
    // Below 2^-14, the smallest normal half: a subnormal k * 2^-24. The float is
    // m * 2^(e - 150) with its 24-bit significand m, so k = m * 2^(e - 126).
    if (f <= 0x33000000u) return sign;  // <= 2^-25: rounds to zero (2^-25 itself is a tie, to the even 0)
    const std::uint32_t e = f >> 23;
    const std::uint32_t m = (f & 0x7fffffu) | 0x800000u;
    return static_cast<std::uint16_t>(sign | shiftRoundEven(m, static_cast<int>(126 - e)));  // may carry into the smallest normal
  }
  // Normal: rebias the exponent (127 -> 15) and round the 23-bit mantissa to 10 bits; a carry
  // out of the mantissa correctly bumps the exponent.
  const std::uint32_t rebased = f - (112u << 23);
  return static_cast<std::uint16_t>(sign | shiftRoundEven(rebased, 13));
}

float halfToFloat(std::uint16_t bits) {
  const std::uint32_t sign = static_cast<std::uint32_t>(bits & 0x8000u) << 16;
  const std::uint32_t exponent = (bits >> 10) & 0x1fu;
  std::uint32_t mantissa = bits & 0x3ffu;
  std::uint32_t f = 0;
  if (exponent == 0x1fu) {
    f = sign | 0x7f800000u | (mantissa << 13);
  } else if (exponent != 0) {
    f = sign | ((exponent + 112u) << 23) | (mantissa << 13);
  } else if (mantissa != 0) {
    // Subnormal: normalise the mantissa into a float.
    int e = -1;
    do {
      ++e;
      mantissa <<= 1;
    } while ((mantissa & 0x400u) == 0);
    f = sign | ((112u - static_cast<std::uint32_t>(e)) << 23) | ((mantissa & 0x3ffu) << 13);
  } else {
    f = sign;
  }
  float out = 0;
  std::memcpy(&out, &f, sizeof out);
  return out;
}

}  // namespace prt::web
