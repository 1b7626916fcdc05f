// 8-bit basis entries of matrix CPCA (docs/transfer-codec.md "8-bit basis entries"),
// internal: one float32 scale per (cluster, basis matrix, shell) and int8 levels within
// +-kBasisLevels. The encoder's estimate, its writer and the decoder all use these, so the
// error the search predicts is the error of what is stored and decoded.
#pragma once

#include <cstdint>
#include <span>

namespace prt::transfer_codec {

// Largest |level| of an 8-bit basis entry (-128 is not used, so the range is symmetric).
inline constexpr int kBasisLevels = 127;

// The scale of one (cluster, basis matrix, shell): the smallest float s with
// s * kBasisLevels >= max |x| (0 when every entry is 0), so every level fits.
float basisScale(std::span<const float> entries);

// The level of `x` at `scale`: round to nearest (ties to even), within +-kBasisLevels.
std::int8_t basisLevel(float x, float scale);

// The decoded entry, float(level) * scale in float: the decoder's exact arithmetic.
inline float basisValue(int level, float scale) { return static_cast<float>(level) * scale; }

}  // namespace prt::transfer_codec
