#include "lighting_block.h"

#include <string>

#include "gl_program.h"
#include "gl_readback.h"
#include "web_shaders.h"

namespace prt::web {

Status LightingBlock::init(bool floatTargets) {
  if (Status s = linkProgram(shaders::k_lighting_combine_vert, shaders::k_discard_frag, &program_, "vLighting"); !s.isOk()) return s;
  cubeShLocation_ = glGetUniformLocation(program_, "uCubeSh");
  environmentLocation_ = glGetUniformLocation(program_, "uEnvironment");
  coeffCountLocation_ = glGetUniformLocation(program_, "uCoeffCount");
  glGenVertexArrays(1, &vao_);
  glGenTransformFeedbacks(1, &feedback_);
  glGenTextures(1, &cubeSh_);
  glBindTexture(GL_TEXTURE_2D, cubeSh_);
  setNearestClamp(GL_TEXTURE_2D);
  const float zeros[kPackedLightingFloats] = {};
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kLightingTexelsPerChannel, 3, 0, GL_RGBA, GL_FLOAT, zeros);
  glBindTexture(GL_TEXTURE_2D, 0);
  if (floatTargets) {
    glGenFramebuffers(1, &cubeShFramebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, cubeShFramebuffer_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, cubeSh_, 0);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      glDeleteFramebuffers(1, &cubeShFramebuffer_);
      cubeShFramebuffer_ = 0;
    }
  }
  glGenBuffers(1, &buffer_);
  glBindBuffer(GL_UNIFORM_BUFFER, buffer_);
  glBufferData(GL_UNIFORM_BUFFER, sizeof zeros, zeros, GL_DYNAMIC_COPY);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  bind();
  return Status::ok();
}

void LightingBlock::uploadCubeSh(const float* packed) {
  glBindTexture(GL_TEXTURE_2D, cubeSh_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kLightingTexelsPerChannel, 3, GL_RGBA, GL_FLOAT, packed);
  glBindTexture(GL_TEXTURE_2D, 0);
}

Status LightingBlock::readCubeSh(float* packed) {
  if (!cubeShFramebuffer_) return Status::error(StatusCode::kInvalidArgument, "the cube-SH texture cannot be read without float render targets");
  glBindFramebuffer(GL_FRAMEBUFFER, cubeShFramebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, kLightingTexelsPerChannel, 3, GL_RGBA, GL_FLOAT, packed);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return Status::ok();
}

void LightingBlock::readFirstTexel() {
  float texel[4];
  if (cubeShFramebuffer_) {
    glBindFramebuffer(GL_FRAMEBUFFER, cubeShFramebuffer_);
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_FLOAT, texel);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  } else {
    glBindBuffer(GL_UNIFORM_BUFFER, buffer_);
    (void)readBoundBuffer(GL_UNIFORM_BUFFER, sizeof texel, texel);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
  }
}

void LightingBlock::combine(const float* environment, int displayOrder) {
  // WebGL forbids a buffer bound for transform feedback to be bound anywhere else.
  glBindBufferBase(GL_UNIFORM_BUFFER, kLightingBlockBinding, 0);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  glUseProgram(program_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, cubeSh_);
  glUniform1i(cubeShLocation_, 0);
  glUniform4fv(environmentLocation_, 3 * kLightingTexelsPerChannel, environment);
  glUniform1i(coeffCountLocation_, displayOrder * displayOrder);
  glBindVertexArray(vao_);
  glEnable(GL_RASTERIZER_DISCARD);
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, feedback_);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer_);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, 3 * kLightingTexelsPerChannel);  // one vec4 each
  glEndTransformFeedback();
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, 0);
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
  glDisable(GL_RASTERIZER_DISCARD);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  bind();
}

void LightingBlock::bind() const { glBindBufferBase(GL_UNIFORM_BUFFER, kLightingBlockBinding, buffer_); }

void LightingBlock::read(float* packed) const {
  glBindBuffer(GL_UNIFORM_BUFFER, buffer_);
  (void)readBoundBuffer(GL_UNIFORM_BUFFER, kPackedLightingFloats * sizeof(float), packed);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
}

}  // namespace prt::web
