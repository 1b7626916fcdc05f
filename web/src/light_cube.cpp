#include "light_cube.h"

#include <string>
#include <vector>

#include "cube_faces.h"
#include "gl_program.h"

namespace prt::web {

void LightCube::release() {
  if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
  if (color_) glDeleteTextures(1, &color_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  framebuffer_ = color_ = depth_ = 0;
  size_ = 0;
}

Status LightCube::resize(int size, bool floatTexels) {
  if (size == size_ && floatTexels == float_ && framebuffer_) return Status::ok();
  release();
  glGenTextures(1, &color_);
  glBindTexture(GL_TEXTURE_2D, color_);
  setNearestClamp(GL_TEXTURE_2D);
  glTexStorage2D(GL_TEXTURE_2D, 1, floatTexels ? GL_RGBA32F : GL_RGBA8, 3 * size, 2 * size);
  glBindTexture(GL_TEXTURE_2D, 0);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, 3 * size, 2 * size);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    release();
    return Status::error(StatusCode::kInvalidArgument,
                         std::string("the light cube's ") + (floatTexels ? "RGBA32F" : "RGBA8") + " framebuffer is incomplete (" +
                             std::to_string(status) + ")");
  }
  size_ = size;
  float_ = floatTexels;
  return Status::ok();
}

void LightCube::render(EmitterRenderer& renderer, std::span<const Emitter> emitters, std::span<const BoundingSphere> bounds,
                       Vec3 center, float nearZ) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, 3 * size_, 2 * size_);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClearDepthf(1.0f);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  for (int face = 0; face < 6; ++face) {
    const AtlasOrigin o = cubeAtlasOrigin(face, size_);
    glViewport(o.x, o.y, size_, size_);
    EmitterView view;
    view.viewProjection = cubeFaceViewProjection(face, center, nearZ);
    view.eye = center;
    view.output = float_ ? EmitterOutput::kLinear : EmitterOutput::kRgbe;
    renderer.begin(view);
    for (std::size_t k = 0; k < emitters.size(); ++k)
      if (sphereTouchesCubeFace(face, center, bounds[k])) renderer.draw(emitters[k]);
    renderer.end();
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Status LightCube::read(CubeMap* out) {
  if (!framebuffer_) return Status::error(StatusCode::kInvalidArgument, "the light cube has no storage");
  const std::size_t texels = static_cast<std::size_t>(3 * size_) * static_cast<std::size_t>(2 * size_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  Status s = Status::ok();
  if (float_) {
    std::vector<float> pixels(texels * 4);
    glReadPixels(0, 0, 3 * size_, 2 * size_, GL_RGBA, GL_FLOAT, pixels.data());
    s = cubeMapFromAtlas(size_, pixels, out);
  } else {
    std::vector<std::uint8_t> pixels(texels * 4);
    glReadPixels(0, 0, 3 * size_, 2 * size_, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    s = cubeMapFromRgbeAtlas(size_, pixels, out);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return s;
}

}  // namespace prt::web
