// The surface sample behind every sampled texel of an asset's transfer textures, re-derived
// from the asset's own geometry and atlases by the rasterisation the bake used
// (atlas_samples.h; deterministic), so a tool can print or check per-texel transfer without
// the scene file.
#pragma once

#include <vector>

#include "baker/texture/atlas_samples.h"
#include "prt/asset.h"
#include "prt/status.h"

namespace prt::bake {

// Every texel of `asset` (a decoded, valid asset with atlases) that holds a surface sample,
// in ascending index. Errors: kInvalidArgument when the asset has no atlases, kCorrupt when
// the rasterisation does not reproduce the asset's coverage (a sampled texel it does not
// reach, or one it reaches that the asset marks otherwise), the rasteriser's errors.
Status assetTexelSamples(const BakedAsset& asset, std::vector<AtlasTexel>* out);

}  // namespace prt::bake
