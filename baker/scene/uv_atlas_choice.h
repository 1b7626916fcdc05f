// Which UV set of a scene the transfer textures use: the lightmap convention puts a
// non-overlapping atlas in TEXCOORD_1 (TEXCOORD_0 is often tiled or mirrored for material
// textures), so TEXCOORD_1 is taken when it is a valid atlas, else TEXCOORD_0 when it is
// one, else the scene needs a generated atlas (docs/transfer-textures.md, "UV atlas").
#pragma once

#include <string>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/scene/uv_atlas_check.h"
#include "prt/status.h"

namespace prt::bake {

struct UvAtlasChoice {
  int texcoord = -1;  // 0 or 1: the glTF set used; -1: none is valid, an atlas must be generated
  UvAtlasReport report;  // of the chosen set (empty when texcoord is -1)
  // Why each set that was not chosen was rejected, one line each, naming the set
  // ("TEXCOORD_1: absent (...)", "TEXCOORD_1: 3 overlapping triangle pairs; ...").
  std::vector<std::string> rejected;
};

// Checks scene.texcoord[1] then [0] against `target` and picks the first valid one. An error
// only for arguments checkUvAtlas cannot use (a target out of range, an inconsistent scene).
Status chooseUvAtlas(const Scene& scene, const UvAtlasTarget& target, UvAtlasChoice* out);

}  // namespace prt::bake
