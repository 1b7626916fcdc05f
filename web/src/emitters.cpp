#include "emitters.h"

#include <algorithm>
#include <cmath>

namespace prt::web {

std::string makeLightMesh(std::vector<float> positions, std::vector<std::uint32_t> indices, LightMesh* out) {
  if (positions.empty() || indices.empty()) return "light mesh is empty";
  if (positions.size() % 3 != 0) return "light mesh positions must be x, y, z triples";
  if (indices.size() % 3 != 0) return "light mesh indices must come 3 per triangle";
  if (indices.size() / 3 > kMaxLightMeshTriangles) {
    return "light mesh has " + std::to_string(indices.size() / 3) + " triangles; at most " +
           std::to_string(kMaxLightMeshTriangles) + " are allowed";
  }
  for (float v : positions)
    if (!std::isfinite(v)) return "light mesh has a non-finite position";
  const std::size_t vertexCount = positions.size() / 3;
  for (std::uint32_t i : indices)
    if (i >= vertexCount) return "light mesh index " + std::to_string(i) + " is out of range (" + std::to_string(vertexCount) + " vertices)";
  Vec3 lo{positions[0], positions[1], positions[2]}, hi = lo;
  for (std::size_t k = 0; k < vertexCount; ++k) {
    const Vec3 p{positions[3 * k], positions[3 * k + 1], positions[3 * k + 2]};
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const Vec3 c = (lo + hi) * 0.5f;
  float r = 0.0f;
  for (std::size_t k = 0; k < vertexCount; ++k) r = std::max(r, length(Vec3{positions[3 * k], positions[3 * k + 1], positions[3 * k + 2]} - c));
  out->positions = std::move(positions);
  out->indices = std::move(indices);
  out->boundCenter = c;
  out->boundRadius = r * 1.0001f + 1e-6f;  // rounding of the distances above
  return "";
}

std::string parseEmitters(std::span<const float> flat, int meshCount, std::vector<Emitter>* out) {
  if (flat.size() % kFloatsPerEmitter != 0) {
    return "lights must hold " + std::to_string(kFloatsPerEmitter) + " floats per light, got " + std::to_string(flat.size());
  }
  const std::size_t count = flat.size() / kFloatsPerEmitter;
  if (count > static_cast<std::size_t>(kMaxEmitters)) {
    return std::to_string(count) + " lights; at most " + std::to_string(kMaxEmitters) + " are allowed";
  }
  static const char* const kFields[kFloatsPerEmitter] = {"shape", "px", "py", "pz", "sizeX", "sizeY", "nx", "ny",
                                                          "nz", "r", "g", "b", "intensity", "meshId", "pad14", "pad15"};
  std::vector<Emitter> parsed(count);
  for (std::size_t k = 0; k < count; ++k) {
    const float* f = &flat[k * kFloatsPerEmitter];
    const std::string where = "light " + std::to_string(k) + ": ";
    for (int i = 0; i < kFloatsPerEmitter; ++i)
      if (!std::isfinite(f[i])) return where + kFields[i] + " is not finite";
    if (f[0] != std::floor(f[0]) || f[0] < 0.0f || f[0] > 3.0f) return where + "shape must be 0 (sphere), 1 (disc), 2 (rect) or 3 (mesh)";
    Emitter& e = parsed[k];
    e.shape = static_cast<EmitterShape>(static_cast<int>(f[0]));
    e.position = {f[1], f[2], f[3]};
    e.sizeX = f[4];
    e.sizeY = f[5];
    if (!(e.sizeX > 0.0f)) return where + "sizeX must be > 0";
    if (e.shape == EmitterShape::kRect && !(e.sizeY > 0.0f)) return where + "sizeY must be > 0";
    const Vec3 n{f[6], f[7], f[8]};
    const float len = length(n);
    if (e.shape == EmitterShape::kDisc || e.shape == EmitterShape::kRect) {
      if (!(len > 1e-12f) || !std::isfinite(len)) return where + "normal (nx, ny, nz) must be non-zero";
      e.normal = n * (1.0f / len);
    }
    for (int i = 9; i <= 12; ++i)
      if (f[i] < 0.0f) return where + kFields[i] + " must be >= 0";
    e.radiance = Rgb{f[9], f[10], f[11]} * f[12];
    if (!std::isfinite(e.radiance.r) || !std::isfinite(e.radiance.g) || !std::isfinite(e.radiance.b)) {
      return where + "colour x intensity overflows";
    }
    if (e.shape == EmitterShape::kMesh) {
      if (f[13] != std::floor(f[13]) || f[13] < 0.0f || f[13] >= static_cast<float>(meshCount)) {
        return where + "meshId " + std::to_string(f[13]) + " is not a mesh added with addLightMesh (" + std::to_string(meshCount) + " meshes)";
      }
      e.meshId = static_cast<int>(f[13]);
    }
  }
  *out = std::move(parsed);
  return "";
}

EmitterFrame emitterFrame(Vec3 n) {
  Vec3 u = std::fabs(n.y) < 0.999f ? cross(Vec3{0, 1, 0}, n) : Vec3{1, 0, 0};
  u = u - n * dot(u, n);
  u = u * (1.0f / length(u));
  return {u, cross(n, u), n};
}

namespace {
// Columns a, b, c (scaled axes) and translation t.
glm::mat4 affine(Vec3 a, Vec3 b, Vec3 c, Vec3 t) {
  return {glm::vec4(toGlm(a), 0.0f), glm::vec4(toGlm(b), 0.0f), glm::vec4(toGlm(c), 0.0f), glm::vec4(toGlm(t), 1.0f)};
}
}  // namespace

glm::mat4 emitterModel(const Emitter& e) {
  switch (e.shape) {
    case EmitterShape::kSphere:
      return affine({e.sizeX, 0, 0}, {0, e.sizeX, 0}, {0, 0, e.sizeX}, e.position);
    case EmitterShape::kDisc:
    case EmitterShape::kRect: {
      const EmitterFrame fr = emitterFrame(e.normal);
      const float hx = e.shape == EmitterShape::kDisc ? e.sizeX : 0.5f * e.sizeX;
      const float hy = e.shape == EmitterShape::kDisc ? e.sizeX : 0.5f * e.sizeY;
      return affine(fr.u * hx, fr.v * hy, fr.n, e.position);
    }
    case EmitterShape::kMesh:
      break;
  }
  return affine({e.sizeX, 0, 0}, {0, e.sizeX, 0}, {0, 0, e.sizeX}, e.position);
}

BoundingSphere emitterBounds(const Emitter& e, std::span<const LightMesh> meshes) {
  switch (e.shape) {
    case EmitterShape::kSphere:
      return {e.position, e.sizeX * 1.7321f};  // the impostor cube's corners
    case EmitterShape::kDisc:
      return {e.position, e.sizeX};
    case EmitterShape::kRect:
      return {e.position, 0.5f * std::sqrt(e.sizeX * e.sizeX + e.sizeY * e.sizeY)};
    case EmitterShape::kMesh:
      break;
  }
  if (e.meshId < 0 || static_cast<std::size_t>(e.meshId) >= meshes.size()) return {e.position, 0.0f};
  const LightMesh& m = meshes[static_cast<std::size_t>(e.meshId)];
  return {e.position + m.boundCenter * e.sizeX, m.boundRadius * e.sizeX};
}

}  // namespace prt::web
