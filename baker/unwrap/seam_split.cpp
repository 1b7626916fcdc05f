#include "baker/unwrap/seam_split.h"

#include <bit>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace prt::bake {
namespace {

template <typename T>
void gather(const std::vector<T>& from, const std::vector<std::uint32_t>& source, std::vector<T>* to) {
  to->clear();
  to->reserve(source.size());
  for (std::uint32_t v : source) to->push_back(from[v]);
}

}  // namespace

Status splitSeams(const Scene& scene, std::span<const Uv> cornerUvs, Scene* out) {
  if (cornerUvs.size() != scene.indices.size()) {
    return Status::error(StatusCode::kInvalidArgument, "splitSeams: " + std::to_string(cornerUvs.size()) +
                                                           " corner UVs for " + std::to_string(scene.indices.size()) +
                                                           " corners");
  }
  const std::size_t n = scene.positions.size();
  // Key: the vertex and the UV's bits (bitwise equality: the same float from Blender is the
  // same corner of one chart; -0 and 0 differ, which only splits a vertex needlessly).
  struct Key {
    std::uint32_t vertex, u, v;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = (static_cast<std::uint64_t>(k.u) << 32 | k.v) * 0x9E3779B97F4A7C15ull;
      return static_cast<std::size_t>(h ^ (static_cast<std::uint64_t>(k.vertex) * 0xC2B2AE3D27D4EB4Full));
    }
  };
  std::unordered_map<Key, std::uint32_t, KeyHash> ids;
  ids.reserve(scene.indices.size());
  std::vector<std::uint32_t> source;  // the original vertex of each new one
  std::vector<Uv> uvs;
  std::vector<std::uint32_t> indices(scene.indices.size());
  for (std::size_t c = 0; c < scene.indices.size(); ++c) {
    const std::uint32_t v = scene.indices[c];
    if (v >= n) return Status::error(StatusCode::kInvalidArgument, "splitSeams: index out of range");
    const Key key{v, std::bit_cast<std::uint32_t>(cornerUvs[c].u), std::bit_cast<std::uint32_t>(cornerUvs[c].v)};
    const auto [it, added] = ids.try_emplace(key, static_cast<std::uint32_t>(source.size()));
    if (added) {
      source.push_back(v);
      uvs.push_back(cornerUvs[c]);
    }
    indices[c] = it->second;
  }
  Scene s;
  gather(scene.positions, source, &s.positions);
  if (scene.normals.size() == n) gather(scene.normals, source, &s.normals);
  if (scene.albedo.size() == n) gather(scene.albedo, source, &s.albedo);
  if (scene.pbr.size() == n) gather(scene.pbr, source, &s.pbr);
  if (scene.specular.size() == n) gather(scene.specular, source, &s.specular);
  if (scene.texcoord[0].size() == n) gather(scene.texcoord[0], source, &s.texcoord[0]);
  // Normal maps ride along: a split vertex keeps its map, the map's own uv and its tangent.
  s.normalMaps = scene.normalMaps;
  if (scene.normalMapOf.size() == n) gather(scene.normalMapOf, source, &s.normalMapOf);
  if (scene.normalMapUv.size() == n) gather(scene.normalMapUv, source, &s.normalMapUv);
  if (scene.tangents.size() == n) gather(scene.tangents, source, &s.tangents);
  s.texcoordAbsent[0] = scene.texcoordAbsent[0];
  s.texcoord[1] = std::move(uvs);
  s.indices = std::move(indices);
  s.triangleObject = scene.triangleObject;  // the triangles keep their order
  s.objectNames = scene.objectNames;
  s.name = scene.name;
  *out = std::move(s);
  return Status::ok();
}

}  // namespace prt::bake
