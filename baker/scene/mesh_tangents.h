// Per-vertex tangent frames for normal-mapped vertices whose glTF primitive has no TANGENT.
//
// glTF asks for MikkTSpace there. No C++ MikkTSpace is packaged for Debian (npm's is a
// WebAssembly module for JavaScript), so this is Lengyel's construction, which MikkTSpace
// refines: each triangle's tangent is the surface direction of increasing u of the map's
// texture coordinates and its bitangent that of *decreasing* v (glTF's v runs down the image,
// and a glTF normal map's +y, green, points up the image); both are summed, weighted by the
// triangle's interior angle at the vertex, then Gram-Schmidt against the vertex normal. The
// two agree wherever the mapping is affine per chart (planes, boxes, cylinders); on curved,
// skewed mappings they differ slightly, which is why files baked against MikkTSpace should
// ship TANGENT (the loader then uses it). docs/transfer-textures.md, "Normal maps".
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "baker/scene/scene.h"
#include "prt/vec3.h"

namespace prt::bake {

// Sets (*tangents)[v] for every v with recompute[v] != 0 from the triangles using v (indices
// 3 per triangle; positions, normals, uvs and recompute one per vertex; tangents resized to
// positions.size(), other entries kept). Triangles with an index out of range, zero UV area
// or non-finite values are ignored. A vertex left with no usable direction (every triangle's
// UVs degenerate) gets a unit vector orthogonal to its normal, handedness +1. Returns how many
// vertices got that fallback. Safe on untrusted input.
std::size_t computeVertexTangents(std::span<const Vec3> positions, std::span<const Vec3> normals,
                                  std::span<const Uv> uvs, std::span<const std::uint32_t> indices,
                                  std::span<const std::uint8_t> recompute, std::vector<Tangent>* tangents);

// A unit vector orthogonal to the unit vector n (deterministic; for frames with no preferred
// direction).
Vec3 anyOrthogonal(Vec3 n);

}  // namespace prt::bake
