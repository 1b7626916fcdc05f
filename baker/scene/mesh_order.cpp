#include "baker/scene/mesh_order.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <numeric>
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

// Which input triangle each output triangle of a cache reordering is: meshoptimizer keeps
// every triangle's corners in their order, so equal corner triples match (stacked copies of
// one triangle are interchangeable and are matched in input order).
std::vector<std::uint32_t> recoverTriangleOrder(const std::vector<std::uint32_t>& before,
                                                const std::vector<std::uint32_t>& after) {
  std::map<std::array<std::uint32_t, 3>, std::vector<std::uint32_t>> where;
  const std::size_t n = before.size() / 3;
  for (std::size_t t = n; t-- > 0;) {  // reversed: pop_back below takes the first input first
    where[{before[3 * t], before[3 * t + 1], before[3 * t + 2]}].push_back(static_cast<std::uint32_t>(t));
  }
  std::vector<std::uint32_t> source(n);
  for (std::size_t t = 0; t < n; ++t) {
    std::vector<std::uint32_t>& list = where[{after[3 * t], after[3 * t + 1], after[3 * t + 2]}];
    source[t] = list.back();
    list.pop_back();
  }
  return source;
}

}  // namespace

void optimizeMeshOrder(Scene* scene) { optimizeMeshOrder(scene, nullptr); }

void optimizeMeshOrder(Scene* scene, std::vector<std::uint32_t>* triangleGroup) {
  const std::size_t vertexCount = scene->positions.size();
  std::vector<std::uint32_t>& indices = scene->indices;
  if (vertexCount == 0 || indices.empty()) return;
  const std::size_t triangles = indices.size() / 3;
  std::vector<std::uint32_t> noGroups;
  std::vector<std::uint32_t>& group = triangleGroup != nullptr && triangleGroup->size() == triangles ? *triangleGroup : noGroups;
  const bool tagged = scene->triangleObject.size() == triangles;
  // Group runs first (a stable sort keeps the input order within a group), then each run in
  // cache order; one group is a single run over the whole buffer, as before groups existed.
  std::vector<std::uint32_t> order(triangles);
  std::iota(order.begin(), order.end(), 0u);
  if (!group.empty()) {
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return group[a] < group[b]; });
  }
  std::vector<std::uint32_t> sorted(indices.size()), sortedGroup(group.empty() ? 0 : triangles),
      sortedObject(tagged ? triangles : 0);
  for (std::size_t t = 0; t < triangles; ++t) {
    for (int k = 0; k < 3; ++k) sorted[3 * t + k] = indices[3 * order[t] + k];
    if (!group.empty()) sortedGroup[t] = group[order[t]];
    if (tagged) sortedObject[t] = scene->triangleObject[order[t]];
  }
  std::vector<unsigned int> reordered(indices.size());
  for (std::size_t begin = 0; begin < triangles;) {
    std::size_t end = begin + 1;
    while (end < triangles && (group.empty() || sortedGroup[end] == sortedGroup[begin])) ++end;
    meshopt_optimizeVertexCache(reordered.data() + 3 * begin, sorted.data() + 3 * begin, 3 * (end - begin), vertexCount);
    if (tagged) {
      // Within a run the objects may differ (one atlas over several objects): follow them.
      const std::vector<std::uint32_t> before(sorted.begin() + 3 * begin, sorted.begin() + 3 * end);
      const std::vector<std::uint32_t> after(reordered.begin() + 3 * begin, reordered.begin() + 3 * end);
      const std::vector<std::uint32_t> source = recoverTriangleOrder(before, after);
      for (std::size_t t = 0; t < source.size(); ++t) scene->triangleObject[begin + t] = sortedObject[begin + source[t]];
    }
    begin = end;
  }
  if (!group.empty()) group = std::move(sortedGroup);
  // Cache order first: the fetch remap below follows the triangle order it produces.
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
