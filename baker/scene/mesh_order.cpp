#include "baker/scene/mesh_order.h"

#include <meshoptimizer.h>

#include <cstdint>
#include <vector>

namespace prt::bake {
namespace {

template <typename T>
void remapArray(std::vector<T>* values, const std::vector<unsigned int>& remap, std::size_t newCount) {
  std::vector<T> out(newCount);
  for (std::size_t i = 0; i < values->size(); ++i) {
    if (remap[i] != ~0u) out[remap[i]] = (*values)[i];
  }
  *values = std::move(out);
}

}  // namespace

void optimizeMeshOrder(Scene* scene) {
  const std::size_t vertexCount = scene->positions.size();
  std::vector<std::uint32_t>& indices = scene->indices;
  if (vertexCount == 0 || indices.empty()) return;
  // Cache order first: the fetch remap below follows the triangle order it produces.
  std::vector<unsigned int> reordered(indices.size());
  meshopt_optimizeVertexCache(reordered.data(), indices.data(), indices.size(), vertexCount);
  std::vector<unsigned int> remap(vertexCount);
  const std::size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), reordered.data(), reordered.size(), vertexCount);
  meshopt_remapIndexBuffer(indices.data(), reordered.data(), reordered.size(), remap.data());
  remapArray(&scene->positions, remap, used);
  remapArray(&scene->normals, remap, used);
  remapArray(&scene->albedo, remap, used);
  if (scene->pbr.size() == vertexCount) remapArray(&scene->pbr, remap, used);
  if (scene->specular.size() == vertexCount) remapArray(&scene->specular, remap, used);
  for (std::vector<Uv>& uv : scene->texcoord) {
    if (uv.size() == vertexCount) remapArray(&uv, remap, used);
  }
  if (scene->normalMapOf.size() == vertexCount) remapArray(&scene->normalMapOf, remap, used);
  if (scene->normalMapUv.size() == vertexCount) remapArray(&scene->normalMapUv, remap, used);
  if (scene->tangents.size() == vertexCount) remapArray(&scene->tangents, remap, used);
}

}  // namespace prt::bake
