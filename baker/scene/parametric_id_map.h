// The parametric id map of bi-scale radiance transfer (Sloan et al. 2003, §5 "parametric
// surfaces"; docs/bi-scale.md): the patch tiled through one of the scene's UV sets, and the
// tangent frames the RTT is looked up in, per vertex.
#pragma once

#include <cstdint>
#include <vector>

#include "baker/scene/scene.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::bake {

struct ParametricIdMap {
  int texcoord = -1;             // the UV set (0 or 1); -1: TEXCOORD_0 if the scene has it, else TEXCOORD_1
  double patchesPerUv = 8.0;     // patch repeats per unit of UV, > 0
};

// The UV set `map` uses on `scene`: its texcoord, or the first the scene has. kInvalidArgument
// naming what is missing (texcoordAbsent's reason) when the set is absent.
Status parametricUvSet(const Scene& scene, const ParametricIdMap& map, int* set);

// Per vertex of `scene`: a unit tangent along increasing u of the UV set (Lengyel's
// construction, mesh_tangents.h, orthogonalised against the normal; a vertex whose triangles
// have no UV area gets any orthogonal direction) and patch coordinates (u, -v) x patchesPerUv:
// glTF's v runs down the image, and the frame's +y, cross(n, t), is the direction of decreasing
// v where the UVs are not mirrored (mirrored charts see the patch mirrored). *fallbacks counts
// the vertices with no UV direction. kInvalidArgument when the set is missing, patchesPerUv is
// not finite and > 0, or a coordinate exceeds kMaxPatchCoordinate (naming the vertex).
Status parametricIdMap(const Scene& scene, const ParametricIdMap& map, std::vector<Vec3>* tangents,
                       std::vector<float>* patchUv, std::size_t* fallbacks);

}  // namespace prt::bake
