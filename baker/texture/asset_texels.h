// The surface sample behind every sampled texel of an asset's transfer textures, re-derived
// from the asset's own geometry and atlases by the rasterisation the bake used
// (atlas_samples.h; deterministic), so a tool can print or check per-texel transfer without
// the scene file.
#pragma once

#include <span>
#include <vector>

#include "baker/texture/atlas_samples.h"
#include "prt/glossy_lobe.h"
#include "prt/asset.h"
#include "prt/status.h"

namespace prt::bake {

// Every texel of `asset` (a decoded, valid asset with atlases) that holds a surface sample,
// in ascending index. Errors: kInvalidArgument when the asset has no atlases, kCorrupt when
// the rasterisation does not reproduce the asset's coverage (a sampled texel it does not
// reach, or one it reaches that the asset marks otherwise), the rasteriser's errors.
Status assetTexelSamples(const BakedAsset& asset, std::vector<AtlasTexel>* out);

// The glossy material at each texel sample (one out per texel, same order): the owner
// triangle's vertex materials (asset.specular) interpolated at the sample's barycentrics,
// f0, f90 and exponent each linearly (as the bake interpolates albedo), which keeps them in
// the ranges the asset allows. Errors: kInvalidArgument when the asset has no specular
// materials, kCorrupt for a sample whose triangle is not the asset's. Safe on untrusted input.
Status assetTexelSpecular(const BakedAsset& asset, std::span<const AtlasTexel> texels, std::vector<SpecularMaterial>* out);

}  // namespace prt::bake
