// The lighting every shading program reads: a uniform buffer of 3 x 16 vec4 (the
// packLighting layout, kPackedLightingFloats floats: client_limits.h; std140 `Lighting`
// block at binding 0), built on the GPU each time its inputs change by
// lighting_combine.vert from the cube-SH texture (16 x 3 RGBA32F, written
// by the GPU projection or uploaded by the CPU one) and the environment's packed SH.
#pragma once

#include <GLES3/gl3.h>

#include "client_limits.h"
#include "prt/status.h"

namespace prt::web {

inline constexpr GLuint kLightingBlockBinding = 0;

class LightingBlock {
 public:
  // `floatTargets`: whether the cube-SH texture can be a render target (GPU projection).
  Status init(bool floatTargets);

  // Framebuffer over the cube-SH texture, 0 without float render targets.
  GLuint cubeShFramebuffer() const { return cubeShFramebuffer_; }
  // Replaces the cube SH (packLighting layout, 192 floats).
  void uploadCubeSh(const float* packed);
  // Reads the cube SH back (synchronous; needs the framebuffer). 192 floats.
  Status readCubeSh(float* packed);

  // Reads one texel of the cube SH (or, without the framebuffer, the block's first vec4)
  // back: a cheap way to wait for every queued GL command.
  void readFirstTexel();

  // Rebuilds the block: cube SH cut to displayOrder^2 coefficients, plus `environment`
  // (packLighting layout, 192 floats, already cut). Leaves the block bound for drawing.
  void combine(const float* environment, int displayOrder);
  // Binds the block to kLightingBlockBinding.
  void bind() const;
  // Reads the block back (synchronous getBufferSubData). 192 floats.
  void read(float* packed) const;

 private:
  GLuint program_ = 0, vao_ = 0, feedback_ = 0;
  GLint cubeShLocation_ = -1, environmentLocation_ = -1, coeffCountLocation_ = -1;
  GLuint cubeSh_ = 0, cubeShFramebuffer_ = 0, buffer_ = 0;
};

}  // namespace prt::web
