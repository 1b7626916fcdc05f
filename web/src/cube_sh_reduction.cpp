#include "cube_sh_reduction.h"

#include <algorithm>
#include <string>
#include <vector>

#include "client_limits.h"
#include "cube_faces.h"
#include "gl_program.h"
#include "prt/cube_sh_weights.h"
#include "prt/sh_basis.h"
#include "transfer_texture.h"
#include "web_shaders.h"

namespace prt::web {

Status CubeShReduction::init() {
  if (Status s = linkProgram(shaders::k_fullscreen_vert, shaders::k_cube_project_frag, &sumRowsProgram_); !s.isOk()) return s;
  if (Status s = linkProgram(shaders::k_fullscreen_vert, shaders::k_cube_sum_frag, &sumBlocksProgram_); !s.isOk()) return s;
  rowsCube_ = glGetUniformLocation(sumRowsProgram_, "uCube");
  rowsWeights_ = glGetUniformLocation(sumRowsProgram_, "uWeights");
  rowsSize_ = glGetUniformLocation(sumRowsProgram_, "uSize");
  rowsGroups_ = glGetUniformLocation(sumRowsProgram_, "uGroups");
  rowsRects_ = glGetUniformLocation(sumRowsProgram_, "uRects");
  blocksPartial_ = glGetUniformLocation(sumBlocksProgram_, "uPartial");
  blocksSize_ = glGetUniformLocation(sumBlocksProgram_, "uSize");
  blocksGroups_ = glGetUniformLocation(sumBlocksProgram_, "uGroups");
  glGenVertexArrays(1, &vao_);
  return Status::ok();
}

void CubeShReduction::release() {
  if (weights_) glDeleteTextures(1, &weights_);
  if (partial_) glDeleteTextures(1, &partial_);
  if (partialFramebuffer_) glDeleteFramebuffers(1, &partialFramebuffer_);
  weights_ = partial_ = partialFramebuffer_ = 0;
  size_ = order_ = groups_ = 0;
}

std::size_t CubeShReduction::weightBytes() const {
  return static_cast<std::size_t>(3 * size_) * static_cast<std::size_t>(2 * size_) * static_cast<std::size_t>(groups_) * 16;
}

Status CubeShReduction::prepare(int size, int order) {
  if (size == size_ && order == order_ && weights_) return Status::ok();
  release();
  const int n = shCoeffCount(order);
  const int groups = texelsForOrder(order);
  const std::size_t bytes = static_cast<std::size_t>(6) * size * size * groups * 16;
  if (bytes > kMaxWeightTableBytes) {
    return Status::error(StatusCode::kInvalidArgument,
                         "the SH weight table for " + std::to_string(size) + "^2 faces at order " + std::to_string(order) + " needs " +
                             std::to_string(bytes >> 20) + " MiB, over the GPU path's budget of " +
                             std::to_string(kMaxWeightTableBytes >> 20) + " MiB");
  }
  glGenTextures(1, &weights_);
  glBindTexture(GL_TEXTURE_2D_ARRAY, weights_);
  setNearestClamp(GL_TEXTURE_2D_ARRAY);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA32F, 3 * size, 2 * size, groups);
  // Rows in chunks of about 16k texels: bounded memory at any size and order.
  const int rowsPerChunk = std::max(1, std::min(size, 16384 / size));
  std::vector<float> weights(static_cast<std::size_t>(rowsPerChunk) * size * n);
  std::vector<float> layer(static_cast<std::size_t>(rowsPerChunk) * size * 4);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int face = 0; face < 6; ++face) {
    const AtlasOrigin o = cubeAtlasOrigin(face, size);
    for (int row = 0; row < size; row += rowsPerChunk) {
      const int rows = std::min(rowsPerChunk, size - row);
      if (Status s = cubeShWeightRows(order, size, face, row, rows, weights); !s.isOk()) {
        release();
        return s;
      }
      const std::size_t texels = static_cast<std::size_t>(rows) * size;
      for (int g = 0; g < groups; ++g) {
        for (std::size_t t = 0; t < texels; ++t)
          for (int k = 0; k < 4; ++k) {
            const int coeff = 4 * g + k;
            layer[4 * t + k] = coeff < n ? weights[t * n + coeff] : 0.0f;
          }
        glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, o.x, o.y + row, g, size, rows, 1, GL_RGBA, GL_FLOAT, layer.data());
      }
    }
  }
  // Partial sums: (row, face * groups + group), one layer per colour channel.
  glGenTextures(1, &partial_);
  glBindTexture(GL_TEXTURE_2D_ARRAY, partial_);
  setNearestClamp(GL_TEXTURE_2D_ARRAY);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA32F, size, 6 * groups, 3);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  glGenFramebuffers(1, &partialFramebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, partialFramebuffer_);
  const GLenum targets[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  for (int c = 0; c < 3; ++c) glFramebufferTextureLayer(GL_FRAMEBUFFER, targets[c], partial_, 0, c);
  glDrawBuffers(3, targets);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const GLenum err = glGetError();
  if (status != GL_FRAMEBUFFER_COMPLETE || err != GL_NO_ERROR) {
    release();
    return Status::error(StatusCode::kInvalidArgument,
                         err == GL_OUT_OF_MEMORY ? "the GPU is out of memory for the light cube's SH weight table"
                                                 : "the GPU projection's float render targets are unusable (status " +
                                                       std::to_string(status) + ", error " + std::to_string(err) + ")");
  }
  size_ = size;
  order_ = order;
  groups_ = groups;
  return Status::ok();
}

void CubeShReduction::run(GLuint cubeTexture, GLuint cubeShFramebuffer, const FaceRect (&rects)[6]) {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glBindVertexArray(vao_);
  // Pass 1: one fragment per (face row, group).
  glBindFramebuffer(GL_FRAMEBUFFER, partialFramebuffer_);
  glViewport(0, 0, size_, 6 * groups_);
  glUseProgram(sumRowsProgram_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, cubeTexture);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, weights_);
  glUniform1i(rowsCube_, 0);
  glUniform1i(rowsWeights_, 1);
  glUniform1i(rowsSize_, size_);
  glUniform1i(rowsGroups_, groups_);
  GLint packedRects[24];
  for (int f = 0; f < 6; ++f) {
    const FaceRect& r = rects[f];
    const GLint v[4] = {r.x0, r.y0, r.x1, r.y1};
    std::copy(v, v + 4, packedRects + 4 * f);
  }
  glUniform4iv(rowsRects_, 6, packedRects);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  // Pass 2: one fragment per (group, channel) of the cube-SH texture.
  glBindFramebuffer(GL_FRAMEBUFFER, cubeShFramebuffer);
  glViewport(0, 0, kLightingTexelsPerChannel, 3);
  glUseProgram(sumBlocksProgram_);
  glBindTexture(GL_TEXTURE_2D_ARRAY, partial_);
  glUniform1i(blocksPartial_, 1);
  glUniform1i(blocksSize_, size_);
  glUniform1i(blocksGroups_, groups_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
}

}  // namespace prt::web
