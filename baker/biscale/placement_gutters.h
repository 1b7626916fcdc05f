// Gutters of a synthesised id map: the texels around each chart take the placement of a
// sampled texel nearby, so a lookup that lands just outside a chart (a nearest or bilinear
// tap at its edge, a coarser mip level) still reads the chart's own cell. Placements are
// indices, so they are copied, never averaged (texel_dilate.h averages transfer values).
#pragma once

#include <cstdint>
#include <span>

#include "prt/asset.h"
#include "prt/status.h"

namespace prt::bake {

// For every atlas (texels numbered atlas after atlas from firstTexel, one entry per atlas plus
// the total), writes to each unsampled texel within `passes` texels (Chebyshev) of a sampled
// one the placement of the sampled texel nearest it (Euclidean, in texels; ties to the lower
// texel index) among those its already-filled 8-neighbours took theirs from: pass k fills
// the ring at distance k. Sampled texels and texels out of reach are left as they are.
// Errors: kInvalidArgument (passes outside 0 … kMaxDilationPasses), kSizeMismatch (firstTexel,
// sampled or placementOfTexel of other sizes than the atlases give). Deterministic.
Status fillPlacementGutters(std::span<const TextureAtlas> atlases, std::span<const std::uint64_t> firstTexel,
                            std::span<const std::uint8_t> sampled, int passes,
                            std::span<std::uint16_t> placementOfTexel);

}  // namespace prt::bake
