// Gutter dilation for transfer textures (docs/transfer-textures.md, "Texel rasterisation"):
// unused texels next to a chart are filled from the chart, so bilinear filtering at a chart's
// edge (which reads up to one texel outside it, more at coarser mip levels) blends valid data
// instead of the empty background. PRTT's Algorithm 1 dilates by 3.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "prt/status.h"

namespace prt::bake {

inline constexpr int kMaxDilationPasses = 1024;
inline constexpr int kMaxDilationChannels = 4096;

// Fills, in `passes` passes, every unused texel within `passes` texels (Chebyshev distance) of
// a used one: each pass sets each still-unfilled texel that has filled 8-neighbours to the
// plain average of those (their values before the pass, accumulated in double), so every
// filled value is a convex combination of used values and a constant chart stays exactly
// constant. `texels`: width × height texels (1 … kMaxAtlasSize each), row-major, `channels`
// floats each, interleaved; `coverage`: width × height, non-zero = used (TexelRaster's).
// Used texels and texels out of reach are never written. `filled`, if not null, receives
// width × height flags: 1 = used or filled, 0 = still empty. Errors, with the texture
// unchanged: kSizeMismatch (texels or coverage of other sizes), kInvalidArgument (size,
// `passes` outside 0 … kMaxDilationPasses, `channels` outside 1 … kMaxDilationChannels),
// kNotFinite (a used texel holds NaN or infinity); kResourceExhausted (out of memory), the
// texture then possibly part-dilated. Safe on untrusted input; deterministic.
Status dilateGutters(std::span<float> texels, int width, int height, int channels,
                     std::span<const std::uint8_t> coverage, int passes, std::vector<std::uint8_t>* filled = nullptr);

}  // namespace prt::bake
