#include "emitter_renderer.h"

#include "gl_program.h"
#include "web_shaders.h"

namespace prt::web {

EmitterRenderer::Geometry EmitterRenderer::makeGeometry(const float* positions, std::size_t floatCount,
                                                        const std::uint32_t* indices, std::size_t indexCount) {
  Geometry g;
  glGenVertexArrays(1, &g.vao);
  glBindVertexArray(g.vao);
  glGenBuffers(1, &g.vertices);
  glBindBuffer(GL_ARRAY_BUFFER, g.vertices);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(floatCount * sizeof(float)), positions, GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glGenBuffers(1, &g.indices);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.indices);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indexCount * sizeof(std::uint32_t)), indices, GL_STATIC_DRAW);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  g.indexCount = static_cast<GLsizei>(indexCount);
  return g;
}

Status EmitterRenderer::init() {
  if (Status s = linkProgram(shaders::k_emitter_vert, shaders::k_emitter_frag, &program_); !s.isOk()) return s;
  model_ = glGetUniformLocation(program_, "uModel");
  viewProjection_ = glGetUniformLocation(program_, "uViewProjection");
  shape_ = glGetUniformLocation(program_, "uShape");
  sphere_ = glGetUniformLocation(program_, "uSphere");
  eye_ = glGetUniformLocation(program_, "uEye");
  radiance_ = glGetUniformLocation(program_, "uRadiance");
  output_ = glGetUniformLocation(program_, "uOutput");
  exposure_ = glGetUniformLocation(program_, "uExposure");
  // Cube [-1,1]^3, corner k = (x, y, z) from bits 0, 1, 2; faces wound counter-clockwise
  // seen from outside.
  float corners[24];
  for (int k = 0; k < 8; ++k) {
    corners[3 * k] = (k & 1) ? 1.0f : -1.0f;
    corners[3 * k + 1] = (k & 2) ? 1.0f : -1.0f;
    corners[3 * k + 2] = (k & 4) ? 1.0f : -1.0f;
  }
  const std::uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  std::uint32_t boxIndices[36];
  for (int f = 0; f < 6; ++f) {
    const std::uint32_t* q = quads[f];
    const std::uint32_t tri[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
    for (int k = 0; k < 6; ++k) boxIndices[6 * f + k] = tri[k];
  }
  box_ = makeGeometry(corners, 24, boxIndices, 36);
  // Unit square in the local xy plane, front face toward +z.
  const float square[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const std::uint32_t squareIndices[6] = {0, 1, 2, 0, 2, 3};
  square_ = makeGeometry(square, 12, squareIndices, 6);
  return Status::ok();
}

int EmitterRenderer::addMesh(const LightMesh& mesh) {
  meshes_.push_back(makeGeometry(mesh.positions.data(), mesh.positions.size(), mesh.indices.data(), mesh.indices.size()));
  return static_cast<int>(meshes_.size()) - 1;
}

void EmitterRenderer::begin(const EmitterView& view) {
  glUseProgram(program_);
  glUniformMatrix4fv(viewProjection_, 1, GL_FALSE, glm::value_ptr(view.viewProjection));
  glUniform3f(eye_, view.eye.x, view.eye.y, view.eye.z);
  glUniform1i(output_, static_cast<int>(view.output));
  glUniform1f(exposure_, view.exposure);
}

void EmitterRenderer::draw(const Emitter& e) {
  const Geometry* g = &square_;
  if (e.shape == EmitterShape::kSphere) {
    g = &box_;
  } else if (e.shape == EmitterShape::kMesh) {
    if (e.meshId < 0 || e.meshId >= meshCount()) return;
    g = &meshes_[static_cast<std::size_t>(e.meshId)];
  }
  const glm::mat4 model = emitterModel(e);
  glUniformMatrix4fv(model_, 1, GL_FALSE, glm::value_ptr(model));
  glUniform1i(shape_, static_cast<int>(e.shape));
  glUniform4f(sphere_, e.position.x, e.position.y, e.position.z, e.sizeX);
  glUniform3f(radiance_, e.radiance.r, e.radiance.g, e.radiance.b);
  // The sphere is cast from the impostor's far faces: they cover its silhouette even when
  // the viewpoint is inside the cube.
  if (e.shape == EmitterShape::kSphere) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
  } else {
    glDisable(GL_CULL_FACE);
  }
  glBindVertexArray(g->vao);
  glDrawElements(GL_TRIANGLES, g->indexCount, GL_UNSIGNED_INT, nullptr);
}

void EmitterRenderer::end() {
  glDisable(GL_CULL_FACE);
  glBindVertexArray(0);
}

}  // namespace prt::web
