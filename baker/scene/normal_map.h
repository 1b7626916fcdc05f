// Shading normals from tangent-space normal maps (glTF material.normalTexture), as the texel
// bake uses them at each texel sample (PRTT §6.2). docs/transfer-textures.md, "Normal maps".
#pragma once

#include <array>
#include <cstdint>

#include "baker/scene/scene.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::bake {

// Ok when scene's normal-map fields are consistent (scene.h): all empty, or normalMapOf,
// normalMapUv and tangents one per position, every map index -1 or a map, the maps
// non-empty, the corners of each triangle on one map. kSizeMismatch / kInvalidArgument
// naming the first problem. Safe on untrusted input.
Status checkNormalMaps(const Scene& scene);

// The map's normal at `uv` in the frame (n, t): the texel bilinearly filtered, decoded
// c -> 2c - 1, x and y scaled by map.scale (glTF 2.0 §3.9.3), made unit, and expressed as
// x t + y b + z n with b = t.handedness cross(n, t). n must be unit; t is re-orthogonalised
// against it (interpolated frames drift). A map sample that decodes to a zero vector, or a
// non-finite input, returns n. Safe on any input.
Vec3 normalMapped(const NormalMap& map, Uv uv, Vec3 n, Tangent t);

// The shading normal of the surface point with barycentrics `bary` on triangle
// (v0, v1, v2) of `scene`: normalMapped at the interpolated normal-map uv and tangent, when
// the triangle's vertices have a normal map; else `normal` unchanged. `normal` is the point's
// unit interpolated normal. Indices must be valid (a trusted path: debug checks only).
Vec3 shadingNormalAt(const Scene& scene, std::array<std::uint32_t, 3> corners, std::array<float, 3> bary,
                     Vec3 normal);

}  // namespace prt::bake
