// The client's dynamic area lights ("emitters"): the flat 16-floats-per-light form JS passes
// to ClientApp::setLights, its validation, and the geometry every emitter is drawn with
// (local frame, model matrix, bounding sphere). GL-free, so it is tested under Node.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "glm_types.h"
#include "prt/vec3.h"

namespace prt::web {

enum class EmitterShape : int { kSphere = 0, kDisc = 1, kRect = 2, kMesh = 3 };

// [shape, px, py, pz, sizeX, sizeY, nx, ny, nz, r, g, b, intensity, meshId, 0, 0]
inline constexpr int kFloatsPerEmitter = 16;
inline constexpr int kMaxEmitters = 1024;
inline constexpr std::size_t kMaxLightMeshTriangles = 1000000;

struct Emitter {
  EmitterShape shape = EmitterShape::kSphere;
  Vec3 position{};
  float sizeX = 1.0f, sizeY = 1.0f;  // sphere/disc: radius; rect: full side lengths; mesh: uniform scale
  Vec3 normal{0, 0, 1};              // unit; disc and rect emit toward it (one-sided)
  Rgb radiance{};                    // colour x intensity, linear, >= 0
  int meshId = -1;                   // kMesh only
};

// A light mesh in its local units, with the bounding sphere of its vertices.
struct LightMesh {
  std::vector<float> positions;        // x, y, z per vertex
  std::vector<std::uint32_t> indices;  // 3 per triangle
  Vec3 boundCenter{};
  float boundRadius = 0.0f;
};

// Validates a light mesh: non-empty, positions a multiple of 3 and finite, indices a
// multiple of 3, each < vertex count, at most kMaxLightMeshTriangles triangles. Returns ""
// and fills *out (computing its bounds), or the reason.
std::string makeLightMesh(std::vector<float> positions, std::vector<std::uint32_t> indices, LightMesh* out);

// Parses `flat` (kFloatsPerEmitter floats per light). Returns "" and replaces *out, or an
// error naming the light index and field ("light 2: sizeX must be > 0"); *out is then
// unchanged. `meshCount`: mesh ids 0..meshCount-1 exist.
std::string parseEmitters(std::span<const float> flat, int meshCount, std::vector<Emitter>* out);

// Orthonormal frame of a disc or rect: u = normalize(+y x n), or +x when n is within about
// 2.6 degrees of vertical; v = n x u (so v is "up" projected onto the plane for any tilted
// n); u x v = n. A rect's sizeX runs along u and sizeY along v.
struct EmitterFrame {
  Vec3 u, v, n;
};
EmitterFrame emitterFrame(Vec3 unitNormal);

// Local-to-world matrix of the emitter's drawn geometry: sphere: the unit cube [-1,1]^3
// around its centre scaled by the radius (an impostor box; the sphere itself is ray-cast);
// disc and rect: the unit square [-1,1]^2 in the (u, v) plane, front face toward n; mesh:
// its local vertices scaled by sizeX and moved by p.
glm::mat4 emitterModel(const Emitter& e);

struct BoundingSphere {
  Vec3 center{};
  float radius = 0.0f;
};
// A sphere holding everything the emitter draws. `meshes` indexed by meshId.
BoundingSphere emitterBounds(const Emitter& e, std::span<const LightMesh> meshes);

}  // namespace prt::web
