// Vertex and triangle order for locality (Debian's libmeshoptimizer): triangles in
// post-transform-cache order, vertices in first-use order. Neighbouring vertices then sit
// close in the asset, so transfer values vary smoothly along every per-vertex array (what
// the transfer codec's planar streams and a general entropy coder exploit) and the GPU
// fetches them coherently.
#pragma once

#include "baker/scene/scene.h"

namespace prt::bake {

// Reorders `scene`'s triangles and vertices in place (every per-vertex array follows the
// same permutation; the mesh, seen as a set of triangles, is unchanged). Deterministic.
// Vertices no triangle references are dropped (the mesh clean-up already removes them).
void optimizeMeshOrder(Scene* scene);

}  // namespace prt::bake
