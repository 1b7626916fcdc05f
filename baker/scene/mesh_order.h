// Vertex and triangle order for locality (Debian's libmeshoptimizer): triangles in
// post-transform-cache order, vertices in first-use order. Neighbouring vertices then sit
// close in the asset, so transfer values vary smoothly along every per-vertex array (what
// the transfer codec's planar streams and a general entropy coder exploit) and the GPU
// fetches them coherently.
#pragma once

#include <cstdint>
#include <vector>

#include "baker/scene/scene.h"

namespace prt::bake {

// Reorders `scene`'s triangles and vertices in place (every per-vertex array follows the
// same permutation, scene->triangleObject follows the triangles; the mesh, seen as a set of
// triangles, is unchanged). Deterministic. Vertices no triangle references are dropped (the
// mesh clean-up already removes them).
void optimizeMeshOrder(Scene* scene);

// As above, with the triangles grouped: `triangleGroup` (one per triangle, e.g. its atlas)
// stably sorted into ascending runs, each run in its own cache order, and permuted with the
// triangles. Empty, or all one group: exactly optimizeMeshOrder(scene). A group vector of
// another length is ignored (treated as empty).
void optimizeMeshOrder(Scene* scene, std::vector<std::uint32_t>* triangleGroup);

}  // namespace prt::bake
