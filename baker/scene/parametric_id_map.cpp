#include "baker/scene/parametric_id_map.h"

#include <cmath>
#include <string>

#include "baker/scene/mesh_tangents.h"
#include "prt/asset.h"

namespace prt::bake {

Status parametricUvSet(const Scene& scene, const ParametricIdMap& map, int* set) {
  if (map.texcoord != -1 && map.texcoord != 0 && map.texcoord != 1) {
    return Status::error(StatusCode::kInvalidArgument, "the patch's UV set must be 0 or 1, got " + std::to_string(map.texcoord));
  }
  const auto has = [&](int k) { return !scene.positions.empty() && scene.texcoord[k].size() == scene.positions.size(); };
  if (map.texcoord >= 0) {
    if (has(map.texcoord)) {
      *set = map.texcoord;
      return Status::ok();
    }
    const std::string& why = scene.texcoordAbsent[map.texcoord];
    return Status::error(StatusCode::kInvalidArgument, "the scene has no TEXCOORD_" + std::to_string(map.texcoord) +
                                                           " for the patch" + (why.empty() ? "" : ": " + why));
  }
  for (int k : {0, 1}) {
    if (has(k)) {
      *set = k;
      return Status::ok();
    }
  }
  return Status::error(StatusCode::kInvalidArgument,
                       "the parametric id map needs texture coordinates, and the scene has neither TEXCOORD_0 (" +
                           scene.texcoordAbsent[0] + ") nor TEXCOORD_1 (" + scene.texcoordAbsent[1] + ")");
}

Status parametricIdMap(const Scene& scene, const ParametricIdMap& map, std::vector<Vec3>* tangents,
                       std::vector<float>* patchUv, std::size_t* fallbacks) {
  if (!(std::isfinite(map.patchesPerUv) && map.patchesPerUv > 0.0)) {
    return Status::error(StatusCode::kInvalidArgument,
                         "patches per UV unit must be finite and > 0, got " + std::to_string(map.patchesPerUv));
  }
  int set = 0;
  PRT_RETURN_IF_ERROR(parametricUvSet(scene, map, &set));
  const std::vector<Uv>& uv = scene.texcoord[set];
  const std::size_t n = scene.positions.size();
  std::vector<float> coords(2 * n);
  for (std::size_t v = 0; v < n; ++v) {
    const double u = uv[v].u * map.patchesPerUv, w = -static_cast<double>(uv[v].v) * map.patchesPerUv;
    if (!(std::fabs(u) <= kMaxPatchCoordinate && std::fabs(w) <= kMaxPatchCoordinate)) {
      return Status::error(StatusCode::kInvalidArgument,
                           "vertex " + std::to_string(v) + "'s UV (" + std::to_string(uv[v].u) + ", " + std::to_string(uv[v].v) +
                               ") times " + std::to_string(map.patchesPerUv) + " patches per UV unit exceeds " +
                               std::to_string(static_cast<int>(kMaxPatchCoordinate)) + " patch widths");
    }
    coords[2 * v] = static_cast<float>(u);
    coords[2 * v + 1] = static_cast<float>(w);
  }
  std::vector<Tangent> frames;
  const std::vector<std::uint8_t> all(n, 1);
  const std::size_t fallback = computeVertexTangents(scene.positions, scene.normals, uv, scene.indices, all, &frames);
  std::vector<Vec3> out(n);
  for (std::size_t v = 0; v < n; ++v) out[v] = frames[v].direction;
  *tangents = std::move(out);
  *patchUv = std::move(coords);
  if (fallbacks != nullptr) *fallbacks = fallback;
  return Status::ok();
}

}  // namespace prt::bake
