// Smooth per-vertex normals for meshes that come without them (glTF primitives lacking
// NORMAL, or whose normals are unusable).
//
// Weighting: each triangle adds its unit normal × its area × its interior angle at the
// vertex. The angle factor (Thürmer & Wüthrich 1998) makes the result independent of how a
// flat region around the vertex happens to be triangulated; the area factor keeps slivers,
// whose normals are the least reliable, from pulling the average. Only triangles that share
// the vertex *index* contribute, so vertices an exporter split (hard edges, UV seams) keep
// per-side normals: a 24-vertex cube gets face normals, a welded sphere radial ones.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/vec3.h"

namespace prt::bake {

// Used for a vertex that no triangle with non-zero area touches.
inline constexpr Vec3 kFallbackNormal{0.0f, 1.0f, 0.0f};

// Sets (*normals)[v] to the unit, area- and angle-weighted average of the normals of the
// triangles using v, for every v with recompute[v] != 0 (every vertex if `recompute` is
// empty); other entries are kept. `normals` is resized to positions.size(). Triangles with
// an index out of range, a non-finite corner or zero area are ignored. A vertex with no
// usable triangle gets kFallbackNormal; one whose contributions cancel (two-sided sheets
// sharing vertices) gets its largest triangle's normal. Returns how many got either fallback.
std::size_t computeVertexNormals(std::span<const Vec3> positions, std::span<const std::uint32_t> indices,
                                 std::span<const std::uint8_t> recompute, std::vector<Vec3>* normals);

}  // namespace prt::bake
