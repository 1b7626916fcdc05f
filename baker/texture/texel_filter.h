// Bilinear reads of a transfer texture at an atlas UV, as the bake's bounce gathers and seam
// stitching need them: the client's filter (texel centres at (x + 0.5) / size, edges clamped)
// restricted to texels that hold data.
#pragma once

#include <cstdint>
#include <span>

#include "baker/scene/scene.h"
#include "prt/asset.h"

namespace prt::bake {

struct TexelTap {
  std::uint64_t texel = 0;  // index across all atlases
  float weight = 0;
};

// The up to 4 bilinear taps of `uv` in `atlas` whose texels have filled[texel] != 0 (indices
// across all atlases, the atlas's texels starting at firstTexel), weights renormalised to sum
// to 1: an empty texel holds no transfer, and blending it in would darken the read. Returns
// the tap count, 0 when no filled texel is in reach. `uv` must be finite.
int bilinearTaps(Uv uv, const TextureAtlas& atlas, std::uint64_t firstTexel, std::span<const std::uint8_t> filled,
                 TexelTap taps[4]);

}  // namespace prt::bake
