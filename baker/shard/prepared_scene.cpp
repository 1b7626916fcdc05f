#include "baker/shard/prepared_scene.h"

#include <string>

#include "baker/shard/byte_io.h"

namespace prt::bake {
namespace {

Status corrupt(const std::string& what) { return Status::error(StatusCode::kCorrupt, "prepared scene: " + what); }

// Vec3, Rgb and SpecularMaterial as the file stores them: packed f32s in field order.
static_assert(sizeof(Vec3) == 12 && sizeof(Rgb) == 12, "positions, normals and albedo are copied as f32 triples");

constexpr std::size_t kSpecularFloats = 5;
static_assert(sizeof(Uv) == 8, "atlas UVs are copied as f32 pairs");

// The flags after the indices: which per-vertex arrays follow.
constexpr std::uint32_t kHasSpecular = 1, kHasAtlasUv = 2;

}  // namespace

std::vector<std::uint8_t> encodePreparedScene(const Scene& scene, std::span<const Uv> atlasUv) {
  std::vector<std::uint8_t> bytes;
  const std::size_t vertices = scene.positions.size();
  bytes.reserve(8 + vertices * 36 + 8 + scene.indices.size() * 4 + 4 + scene.specular.size() * kSpecularFloats * 4 +
                atlasUv.size() * sizeof(Uv));
  ByteWriter w(&bytes);
  w.u64(vertices);
  w.raw(scene.positions.data(), vertices * sizeof(Vec3));
  w.raw(scene.normals.data(), scene.normals.size() * sizeof(Vec3));
  w.raw(scene.albedo.data(), scene.albedo.size() * sizeof(Rgb));
  w.u64(scene.indices.size());
  w.raw(scene.indices.data(), scene.indices.size() * sizeof(std::uint32_t));
  w.u32((scene.specular.empty() ? 0 : kHasSpecular) | (atlasUv.empty() ? 0 : kHasAtlasUv));
  // Glossy bakes only (the split fills them): a changed roughness or specular factor changes
  // the matrices without touching the albedo.
  for (const SpecularMaterial& m : scene.specular) w.floats(std::span<const float>({m.f0.r, m.f0.g, m.f0.b, m.f90, m.exponent}));
  // Texel bakes only: the atlas the plan picked or generated, on the prepared vertices.
  w.raw(atlasUv.data(), atlasUv.size() * sizeof(Uv));
  return bytes;
}

Status decodePreparedScene(std::span<const std::uint8_t> payload, Scene* out, std::vector<Uv>* atlasUv) {
  ByteReader r(payload);
  std::uint64_t vertices = 0, indices = 0;
  if (!r.u64(&vertices) || vertices > r.remaining() / 36) return corrupt("the vertex arrays are cut short");
  Scene s;
  s.positions.resize(vertices);
  s.normals.resize(vertices);
  s.albedo.resize(vertices);
  r.raw(s.positions.data(), vertices * sizeof(Vec3));
  r.raw(s.normals.data(), vertices * sizeof(Vec3));
  r.raw(s.albedo.data(), vertices * sizeof(Rgb));
  if (!r.u64(&indices) || indices > r.remaining() / 4 || indices % 3 != 0) {
    return corrupt("the index count is cut short, too large or not a multiple of 3");
  }
  s.indices.resize(indices);
  r.raw(s.indices.data(), indices * sizeof(std::uint32_t));
  for (std::uint32_t i : s.indices) {
    if (i >= vertices) return corrupt("index " + std::to_string(i) + " is not below the " + std::to_string(vertices) + " vertices");
  }
  std::uint32_t flags = 0;
  if (!r.u32(&flags) || (flags & ~(kHasSpecular | kHasAtlasUv)) != 0) return corrupt("the flags are cut short or unknown");
  const std::uint64_t specularBytes = (flags & kHasSpecular) ? vertices * kSpecularFloats * 4 : 0;
  const std::uint64_t uvBytes = (flags & kHasAtlasUv) ? vertices * sizeof(Uv) : 0;
  if (r.remaining() != specularBytes + uvBytes) {
    return corrupt(std::to_string(r.remaining()) + " bytes after the indices, not the " + std::to_string(specularBytes + uvBytes) +
                   " of the specular materials and atlas UVs the flags announce");
  }
  if (flags & kHasSpecular) {
    std::vector<float> f;
    r.floats(vertices * kSpecularFloats, &f);
    s.specular.resize(vertices);
    for (std::size_t v = 0; v < vertices; ++v) {
      const float* m = &f[v * kSpecularFloats];
      s.specular[v].f0 = {m[0], m[1], m[2]};
      s.specular[v].f90 = m[3];
      s.specular[v].exponent = m[4];
    }
  }
  std::vector<Uv> uv(flags & kHasAtlasUv ? vertices : 0);
  r.raw(uv.data(), uv.size() * sizeof(Uv));
  if (atlasUv) *atlasUv = std::move(uv);
  *out = std::move(s);
  return Status::ok();
}

}  // namespace prt::bake
