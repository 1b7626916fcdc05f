#include "baker/scene/uv_atlas_sets.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prt::bake {
namespace {

template <typename T>
void gatherInto(const std::vector<T>& from, const std::vector<std::uint32_t>& source, std::size_t n, std::vector<T>* to) {
  to->clear();
  if (from.size() != n) return;
  to->reserve(source.size());
  for (std::uint32_t v : source) to->push_back(from[v]);
}

// Appends b to a when both had the array (a at its old vertex count, b at its own), else
// drops it: an optional per-vertex array is meaningful only when every vertex has it.
template <typename T>
void concat(std::vector<T>* a, std::size_t aVertices, bool aFirst, std::vector<T>&& b, std::size_t bVertices) {
  if (aFirst) {
    *a = std::move(b);
    if (a->size() != bVertices) a->clear();
    return;
  }
  if (a->size() != aVertices || b.size() != bVertices) {
    a->clear();
    return;
  }
  a->insert(a->end(), b.begin(), b.end());
}

}  // namespace

SceneObjects sceneObjects(const Scene& scene) {
  SceneObjects out;
  const std::size_t triangles = scene.indices.size() / 3;
  if (scene.triangleObject.size() != triangles) {
    out.triangles.emplace_back(triangles);
    for (std::size_t t = 0; t < triangles; ++t) out.triangles[0][t] = static_cast<std::uint32_t>(t);
    out.names.push_back(scene.name.empty() ? "the scene" : scene.name);
    return out;
  }
  std::uint32_t maxObject = 0;
  for (std::uint32_t o : scene.triangleObject) maxObject = std::max(maxObject, o);
  std::vector<std::vector<std::uint32_t>> byObject(triangles == 0 ? 0 : std::size_t{maxObject} + 1);
  for (std::size_t t = 0; t < triangles; ++t) byObject[scene.triangleObject[t]].push_back(static_cast<std::uint32_t>(t));
  for (std::size_t o = 0; o < byObject.size(); ++o) {
    if (byObject[o].empty()) continue;
    out.triangles.push_back(std::move(byObject[o]));
    out.names.push_back(o < scene.objectNames.size() ? scene.objectNames[o] : "object " + std::to_string(o));
  }
  return out;
}

Scene scenePart(const Scene& scene, std::span<const std::uint32_t> triangles) {
  const std::size_t n = scene.positions.size();
  constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> newIndex(n, kUnset), source;
  Scene s;
  s.indices.reserve(3 * triangles.size());
  for (std::uint32_t t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = scene.indices[3 * std::size_t{t} + k];
      if (newIndex[v] == kUnset) {
        newIndex[v] = static_cast<std::uint32_t>(source.size());
        source.push_back(v);
      }
      s.indices.push_back(newIndex[v]);
    }
    if (scene.triangleObject.size() == scene.indices.size() / 3) s.triangleObject.push_back(scene.triangleObject[t]);
  }
  gatherInto(scene.positions, source, n, &s.positions);
  gatherInto(scene.normals, source, n, &s.normals);
  gatherInto(scene.albedo, source, n, &s.albedo);
  gatherInto(scene.pbr, source, n, &s.pbr);
  gatherInto(scene.specular, source, n, &s.specular);
  for (int set = 0; set < 2; ++set) {
    gatherInto(scene.texcoord[set], source, n, &s.texcoord[set]);
    s.texcoordAbsent[set] = scene.texcoordAbsent[set];
  }
  s.normalMaps = scene.normalMaps;
  gatherInto(scene.normalMapOf, source, n, &s.normalMapOf);
  gatherInto(scene.normalMapUv, source, n, &s.normalMapUv);
  gatherInto(scene.tangents, source, n, &s.tangents);
  s.objectNames = scene.objectNames;
  s.name = scene.name;
  return s;
}

void appendScenePart(Scene* into, Scene&& part) {
  const bool first = into->indices.empty() && into->positions.empty();
  const std::size_t a = into->positions.size(), b = part.positions.size();
  const auto base = static_cast<std::uint32_t>(a);
  for (std::uint32_t v : part.indices) into->indices.push_back(base + v);
  const std::size_t aTriangles = into->triangleObject.size();
  concat(&into->triangleObject, aTriangles, first, std::move(part.triangleObject), part.triangleObject.size());
  concat(&into->positions, a, first, std::move(part.positions), b);
  concat(&into->normals, a, first, std::move(part.normals), b);
  concat(&into->albedo, a, first, std::move(part.albedo), b);
  concat(&into->pbr, a, first, std::move(part.pbr), b);
  concat(&into->specular, a, first, std::move(part.specular), b);
  for (int set = 0; set < 2; ++set) concat(&into->texcoord[set], a, first, std::move(part.texcoord[set]), b);
  concat(&into->normalMapOf, a, first, std::move(part.normalMapOf), b);
  concat(&into->normalMapUv, a, first, std::move(part.normalMapUv), b);
  concat(&into->tangents, a, first, std::move(part.tangents), b);
  if (first) {
    into->normalMaps = std::move(part.normalMaps);
    into->objectNames = std::move(part.objectNames);
    into->name = std::move(part.name);
    for (int set = 0; set < 2; ++set) into->texcoordAbsent[set] = std::move(part.texcoordAbsent[set]);
  }
}

double surfaceArea(const Scene& scene) {
  double surface = 0.0;
  for (std::size_t i = 0; i + 2 < scene.indices.size(); i += 3) {
    const Vec3 a = scene.positions[scene.indices[i]], b = scene.positions[scene.indices[i + 1]],
               c = scene.positions[scene.indices[i + 2]];
    surface += 0.5 * length(cross(b - a, c - a));
  }
  return surface;
}

double uvArea(const Scene& scene, std::span<const Uv> uv) {
  double area = 0.0;
  if (uv.size() != scene.positions.size()) return 0.0;
  for (std::size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
    const std::uint32_t a = scene.indices[t], b = scene.indices[t + 1], c = scene.indices[t + 2];
    const double du1 = uv[b].u - uv[a].u, dv1 = uv[b].v - uv[a].v, du2 = uv[c].u - uv[a].u, dv2 = uv[c].v - uv[a].v;
    area += 0.5 * std::abs(du1 * dv2 - dv1 * du2);
  }
  return area;
}

double fitUvsToSquare(const Scene& scene, std::vector<Uv>* uvs) {
  if (uvs->size() != scene.positions.size() || scene.indices.empty()) return 1.0;
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (std::uint32_t v : scene.indices) {
    const Uv& p = (*uvs)[v];
    lo[0] = std::min(lo[0], double{p.u}), hi[0] = std::max(hi[0], double{p.u});
    lo[1] = std::min(lo[1], double{p.v}), hi[1] = std::max(hi[1], double{p.v});
  }
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  if (!(extent > 0.0) || !std::isfinite(extent) || !std::isfinite(lo[0]) || !std::isfinite(lo[1])) return 1.0;
  const double scale = 1.0 / extent;
  for (Uv& p : *uvs) {
    p.u = static_cast<float>(std::clamp((p.u - lo[0]) * scale, 0.0, 1.0));
    p.v = static_cast<float>(std::clamp((p.v - lo[1]) * scale, 0.0, 1.0));
  }
  return scale;
}

}  // namespace prt::bake
