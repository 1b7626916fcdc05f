// Clean-up of triangle soups before baking: triangles that cannot be shaded or traced
// meaningfully are dropped, and vertices nothing references any more are removed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/vec3.h"
#include "baker/scene/scene.h"

namespace prt::bake {

// A triangle counts as zero-area when twice its area is at most this fraction of its
// longest edge squared (height below ~1e-7 of its length): at float resolution its normal
// would be rounding noise. Exactly collinear or coincident corners always qualify.
inline constexpr double kDegenerateRelativeArea = 1e-7;

struct TriangleCleanupStats {
  std::size_t nonFinite = 0;   // a corner position is NaN or infinite
  std::size_t zeroArea = 0;    // see kDegenerateRelativeArea (includes repeated indices)
  std::size_t outOfRange = 0;  // an index >= positions.size()
};

// Removes from `indices` (3 per triangle; a trailing partial triangle is removed too) every
// triangle with an out-of-range index, a non-finite corner or zero area, keeping the order
// of the rest; returns how many of each kind went. `triangleTags` (one per triangle, e.g.
// Scene::triangleObject), when given and of that length, loses the same triangles.
TriangleCleanupStats removeBadTriangles(std::span<const Vec3> positions, std::vector<std::uint32_t>* indices,
                                        std::vector<std::uint32_t>* triangleTags = nullptr);

// Removes vertices that no triangle references from positions, normals and albedo (which
// must have equal lengths, or the call does nothing and returns 0), keeping their order and
// renumbering indices; every index must be in range. Returns how many vertices went.
std::size_t removeUnreferencedVertices(Scene* scene);

}  // namespace prt::bake
