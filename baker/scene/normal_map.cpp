#include "baker/scene/normal_map.h"

#include <cassert>
#include <cmath>

namespace prt::bake {

Status checkNormalMaps(const Scene& scene) {
  const std::size_t n = scene.positions.size();
  if (scene.normalMapOf.empty()) {
    if (!scene.normalMapUv.empty() || !scene.tangents.empty()) {
      return Status::error(StatusCode::kSizeMismatch, "normal-map uvs or tangents without normal-map indices");
    }
    return Status::ok();
  }
  if (scene.normalMapOf.size() != n || scene.normalMapUv.size() != n || scene.tangents.size() != n) {
    return Status::error(StatusCode::kSizeMismatch, "normal-map indices, uvs and tangents must be one per vertex (" +
                                                        std::to_string(n) + ")");
  }
  for (std::size_t m = 0; m < scene.normalMaps.size(); ++m) {
    const LinearTexture& t = scene.normalMaps[m].texture;
    if (t.width < 1 || t.height < 1 ||
        t.rgb.size() != static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height) * 3) {
      return Status::error(StatusCode::kInvalidArgument, "normal map " + std::to_string(m) + " has no valid texels");
    }
  }
  for (std::size_t v = 0; v < n; ++v) {
    const std::int32_t m = scene.normalMapOf[v];
    if (m < -1 || m >= static_cast<std::int64_t>(scene.normalMaps.size())) {
      return Status::error(StatusCode::kInvalidArgument,
                           "vertex " + std::to_string(v) + " names normal map " + std::to_string(m) + " of " +
                               std::to_string(scene.normalMaps.size()));
    }
  }
  for (std::size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
    const std::uint32_t a = scene.indices[t], b = scene.indices[t + 1], c = scene.indices[t + 2];
    if (a >= n || b >= n || c >= n) continue;  // the bake's own index check names it
    if (scene.normalMapOf[a] != scene.normalMapOf[b] || scene.normalMapOf[a] != scene.normalMapOf[c]) {
      return Status::error(StatusCode::kInvalidArgument,
                           "triangle " + std::to_string(t / 3) + " has corners on different normal maps");
    }
  }
  return Status::ok();
}

Vec3 normalMapped(const NormalMap& map, Uv uv, Vec3 n, Tangent t) {
  const Rgb c = sampleBilinear(map.texture, uv.u, uv.v, map.wrapS, map.wrapT);
  const Vec3 local{(2.0f * c.r - 1.0f) * map.scale, (2.0f * c.g - 1.0f) * map.scale, 2.0f * c.b - 1.0f};
  const float localLength = length(local);
  Vec3 tangent = t.direction - n * dot(n, t.direction);
  const float tangentLength = length(tangent);
  if (!(localLength > 0.0f) || !std::isfinite(localLength) || !(tangentLength > 1e-6f) || !isFinite(n)) return n;
  tangent = tangent * (1.0f / tangentLength);
  const Vec3 bitangent = cross(n, tangent) * (t.handedness < 0.0f ? -1.0f : 1.0f);
  const Vec3 m = tangent * local.x + bitangent * local.y + n * local.z;
  const float len = length(m);
  return len > 0.0f && std::isfinite(len) ? m * (1.0f / len) : n;
}

Vec3 shadingNormalAt(const Scene& scene, std::array<std::uint32_t, 3> corners, std::array<float, 3> bary,
                     Vec3 normal) {
  if (scene.normalMapOf.empty()) return normal;
  assert(corners[0] < scene.normalMapOf.size() && corners[1] < scene.normalMapOf.size() &&
         corners[2] < scene.normalMapOf.size());
  const std::int32_t map = scene.normalMapOf[corners[0]];
  if (map < 0 || static_cast<std::size_t>(map) >= scene.normalMaps.size()) return normal;
  Uv uv;
  Tangent t{Vec3{0, 0, 0}, scene.tangents[corners[0]].handedness};
  for (int k = 0; k < 3; ++k) {
    const Uv& c = scene.normalMapUv[corners[k]];
    uv.u += bary[k] * c.u;
    uv.v += bary[k] * c.v;
    t.direction = t.direction + scene.tangents[corners[k]].direction * bary[k];
  }
  return normalMapped(scene.normalMaps[static_cast<std::size_t>(map)], uv, normal, t);
}

}  // namespace prt::bake
