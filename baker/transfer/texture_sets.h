// Texture sets (PRTT §4.3): how many atlases a texel bake uses and which UVs each takes, per
// TexelBakeSettings::sets (docs/transfer-textures.md, "Texture sets"). Runs before the vertex
// order is optimised, since a generated atlas or a split into objects changes the vertices.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/transfer/bake_asset.h"
#include "prt/status.h"

namespace prt::bake {

struct TextureSetPlan {
  int texcoord = -1;  // the scene's set holding every atlas's UVs after planning (0 or 1)
  // One per atlas, in atlas order; charts, size, texcoord and generated filled, the texel
  // counts left for the bake.
  std::vector<TexelAtlasReport> atlases;
  // Per triangle of the planned scene, its atlas (0 .. atlases.size() - 1): the group
  // optimizeMeshOrder keeps contiguous. Empty with one atlas.
  std::vector<std::uint32_t> triangleAtlas;
  std::vector<std::string> rejected;  // the UV sets not used, one line each, naming the set (and object)
  std::string reason;                 // why one atlas or one per object
};

// Plans the texture set of *scene for `t`; may replace *scene by one whose vertices are split
// (per object: vertices shared between objects duplicated, the objects' atlases as texcoord[1];
// generated: split at the charts' seams). Errors: no valid set and no generator (each set's
// reason, naming the object), more than kMaxAssetAtlases objects under TextureSets::kObject
// (naming the first object past the limit), the generator's, a size out of range.
Status planTextureSets(const TexelBakeSettings& t, Scene* scene, TextureSetPlan* plan);

}  // namespace prt::bake
