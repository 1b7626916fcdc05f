// IEEE-754 binary16 ("half") conversion: the transfer codec's float16 settings
// (docs/transfer-codec.md) and the web client's RGBA16F transfer textures.
// Written out bit by bit rather than with _Float16 or F16C so that native and wasm builds
// agree exactly and no target feature is needed.
#pragma once

#include <cstdint>

namespace prt {

// Nearest binary16 to `value`, ties to even. Values whose magnitude rounds past 65504
// become +-infinity; NaN stays NaN (quiet, payload dropped). Subnormals are produced.
std::uint16_t floatToHalf(float value) noexcept;

// The exact binary32 value of binary16 `bits` (every half is representable as a float).
float halfToFloat(std::uint16_t bits) noexcept;

// True when `bits` is a finite half (exponent field not all ones).
constexpr bool isFiniteHalf(std::uint16_t bits) noexcept { return (bits & 0x7c00u) != 0x7c00u; }

// The largest finite half, 65504.
inline constexpr float kMaxHalf = 65504.0f;

}  // namespace prt
