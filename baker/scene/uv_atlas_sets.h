// The pieces of a texture set (PRTT §4.3, docs/transfer-textures.md "Texture sets"): a scene
// cut into its objects, each object's UVs fitted to a square of its own, the measures that
// decide whether one atlas wastes texels, and the parts put back together, grouped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "baker/scene/scene.h"

namespace prt::bake {

// The triangles of each object, in ascending object index, objects without triangles left
// out; a scene without triangleObject is one object. `names[k]` labels part k (the object's
// name, else "object N", else the scene's name).
struct SceneObjects {
  std::vector<std::vector<std::uint32_t>> triangles;
  std::vector<std::string> names;
};
SceneObjects sceneObjects(const Scene& scene);

// The sub-scene of `triangles` (indices into scene's triangles, in that order): its vertices
// in first-use order with every per-vertex array, normal maps and object tables copied, so a
// vertex several objects share is duplicated into each. Indices must be in range.
Scene scenePart(const Scene& scene, std::span<const std::uint32_t> triangles);

// Appends `part`'s triangles and vertices to *into (indices offset, per-vertex arrays
// concatenated; an optional array, e.g. pbr, is kept only when every part has it). Parts must
// come from one scene (scenePart), so their normal maps and object tables are the same.
void appendScenePart(Scene* into, Scene&& part);

// Surface area of all triangles (square metres) and UV area of set `uvs` (one per vertex, in
// UV units squared, each triangle's absolute area).
double surfaceArea(const Scene& scene);
double uvArea(const Scene& scene, std::span<const Uv> uvs);

// Maps `uvs` (those the triangles reference) by one uniform scale and offset so their bounding
// box starts at (0, 0) and its longer side spans [0, 1]: an object's piece of a scene-wide
// layout then fills a square atlas of its own. Clamped to [0, 1] against rounding. A set with
// an empty or non-finite box is left as it is. Returns the scale (1 when left).
double fitUvsToSquare(const Scene& scene, std::vector<Uv>* uvs);

}  // namespace prt::bake
