// GL drawing of emitters (emitters.h) with shaders/emitter.*: into the main view
// (tone-mapped, depth-tested against the scene) and into the light cube's faces (linear
// float or RGBE8 radiance).
#pragma once

#include <GLES3/gl3.h>

#include <vector>

#include "emitters.h"
#include "glm_types.h"
#include "prt/status.h"

namespace prt::web {

enum class EmitterOutput : int { kLinear = 0, kRgbe = 1, kDisplay = 2 };

struct EmitterView {
  glm::mat4 viewProjection{1.0f};
  Vec3 eye{};  // viewpoint the sphere impostors cast rays from
  EmitterOutput output = EmitterOutput::kLinear;
  float exposure = 1.0f;  // kDisplay only
};

class EmitterRenderer {
 public:
  // Compiles the program and builds the impostor cube and unit square; context current.
  Status init();
  // Uploads a validated mesh; its id is the number of meshes before it.
  int addMesh(const LightMesh& mesh);
  int meshCount() const { return static_cast<int>(meshes_.size()); }

  // Sets the program and per-view uniforms; then draw() each emitter. The caller owns the
  // framebuffer, viewport and depth state; draw() sets face culling and leaves it off.
  void begin(const EmitterView& view);
  void draw(const Emitter& e);
  void end();

 private:
  struct Geometry {
    GLuint vao = 0, vertices = 0, indices = 0;
    GLsizei indexCount = 0;
  };
  static Geometry makeGeometry(const float* positions, std::size_t floatCount, const std::uint32_t* indices, std::size_t indexCount);

  GLuint program_ = 0;
  GLint model_ = -1, viewProjection_ = -1, shape_ = -1, sphere_ = -1, eye_ = -1, radiance_ = -1, output_ = -1, exposure_ = -1;
  Geometry box_, square_;
  std::vector<Geometry> meshes_;
};

}  // namespace prt::web
