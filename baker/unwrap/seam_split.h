// Gives a scene per-corner UVs (a generated atlas) by splitting its vertices where corners of
// one vertex got different UVs (chart seams), so the atlas is one UV per vertex like a glTF set.
#pragma once

#include <span>

#include "baker/scene/scene.h"
#include "prt/status.h"

namespace prt::bake {

// `scene` with one vertex per distinct (vertex, UV) pair of its corners (`cornerUvs[c]` is the
// UV of corner c = indices[c]) and those UVs as texcoord[1], the lightmap set; every other
// per-vertex array is copied to the split vertices. Deterministic: new vertices are numbered in
// order of first use. kInvalidArgument when cornerUvs does not have one UV per index.
Status splitSeams(const Scene& scene, std::span<const Uv> cornerUvs, Scene* out);

}  // namespace prt::bake
