#include "texel_renderer.h"

#include <algorithm>
#include <string>

#include "gl_program.h"
#include "lighting_block.h"
#include "texel_texture.h"
#include "transfer_texture.h"
#include "web_shaders.h"

namespace prt::web {

Status TexelRenderer::link(const char* fs, Program* out) {
  GLuint p = 0;
  if (Status s = linkProgram(shaders::k_texel_prt_vert, fs, &p); !s.isOk()) return s;
  bindUniformBlock(p, "Lighting", kLightingBlockBinding);
  out->id = p;
  out->viewProjection = glGetUniformLocation(p, "uViewProjection");
  out->atlasSpace = glGetUniformLocation(p, "uAtlasSpace");
  out->transfer = glGetUniformLocation(p, "uTransfer");
  out->layersPerChannel = glGetUniformLocation(p, "uLayersPerChannel");
  out->channels = glGetUniformLocation(p, "uChannels");
  out->activeLayers = glGetUniformLocation(p, "uActiveLayers");
  out->exposure = glGetUniformLocation(p, "uExposure");
  out->atlasSize = glGetUniformLocation(p, "uAtlasSize");
  return Status::ok();
}

Status TexelRenderer::init() {
  if (Status s = link(shaders::k_texel_prt_frag, &shading_); !s.isOk()) return s;
  return link(shaders::k_depth_only_frag, &depth_);
}

void TexelRenderer::releasePass(Pass* p) {
  if (!p->textures.empty()) glDeleteTextures(static_cast<GLsizei>(p->textures.size()), p->textures.data());
  *p = {};
}

void TexelRenderer::releaseGeometry() {
  for (Pass& p : passes_) releasePass(&p);
  if (atlasUv_) glDeleteBuffers(1, &atlasUv_);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  atlasUv_ = 0;
  vao_ = 0;
  indexCount_ = 0;
  atlases_.clear();
}

void TexelRenderer::setGeometry(GLuint positions, GLuint albedo, GLuint indices, std::span<const float> atlasUv,
                                std::span<const TextureAtlas> atlases) {
  releaseGeometry();
  if (atlases.empty()) return;
  atlases_.assign(atlases.begin(), atlases.end());
  const TextureAtlas& last = atlases_.back();
  indexCount_ = static_cast<GLsizei>(3 * (last.firstTriangle + last.triangleCount));
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, positions);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, albedo);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glGenBuffers(1, &atlasUv_);
  glBindBuffer(GL_ARRAY_BUFFER, atlasUv_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(atlasUv.size() * sizeof(float)), atlasUv.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(7);
  glVertexAttribPointer(7, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

Status TexelRenderer::uploadPass(const TransferPass& pass, int order) {
  const auto kind = static_cast<std::size_t>(pass.kind);
  if (kind > 2 || atlases_.empty()) {
    return Status::error(StatusCode::kInvalidArgument, "uploadTexelPass: no atlases, or a pass kind out of range");
  }
  GLint maxSize = 2048, maxLayers = 256;  // the WebGL2 minimums
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  // Pack first: nothing on the GPU changes if the pass does not fit.
  TexelTextures packed;
  if (Status s = packTexelTransfer(pass, order, atlases_, maxSize, maxLayers, &packed); !s.isOk()) return s;
  Pass next;
  next.channels = packed.channels;
  next.order = packed.order;
  next.layersPerChannel = packed.layersPerChannel;
  next.textures.assign(packed.atlases.size(), 0);
  glGenTextures(static_cast<GLsizei>(next.textures.size()), next.textures.data());
  for (std::size_t a = 0; a < packed.atlases.size(); ++a) {
    const TexelAtlasTexture& t = packed.atlases[a];
    glBindTexture(GL_TEXTURE_2D_ARRAY, next.textures[a]);
    // Bilinear within a layer (the dilated gutters keep the background out of it), no mipmaps.
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA16F, t.width, t.height, t.layers, 0, GL_RGBA, GL_HALF_FLOAT, t.halves.data());
  }
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  if (Status s = glErrorStatus("this scene's transfer textures", "uploading a texel pass"); !s.isOk()) {
    releasePass(&next);
    return s;
  }
  releasePass(&passes_[kind]);
  passes_[kind] = std::move(next);
  return Status::ok();
}

int TexelRenderer::passOrder(int kind) const {
  if (kind < 0 || kind > 2) return 0;
  return passes_[static_cast<std::size_t>(kind)].order;
}

void TexelRenderer::useShading(const Pass& p, int displayOrder, float exposure, int atlas) {
  glUseProgram(shading_.id);
  glUniform1i(shading_.atlasSpace, atlas >= 0 ? 1 : 0);
  if (atlas >= 0) {
    const TextureAtlas& a = atlases_[static_cast<std::size_t>(atlas)];
    glUniform2f(shading_.atlasSize, static_cast<float>(a.width), static_cast<float>(a.height));
  }
  glUniform1i(shading_.transfer, 0);
  glUniform1i(shading_.layersPerChannel, p.layersPerChannel);
  glUniform1i(shading_.channels, p.channels);
  // A pass still streaming holds fewer bands than the asset: shade with those.
  glUniform1i(shading_.activeLayers, texelsForOrder(std::clamp(std::min(displayOrder, p.order), 1, p.order)));
  glUniform1f(shading_.exposure, exposure);
  glActiveTexture(GL_TEXTURE0);
}

void TexelRenderer::drawAtlas(std::size_t atlas) const {
  const TextureAtlas& a = atlases_[atlas];
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * a.triangleCount), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(static_cast<std::uintptr_t>(3u * a.firstTriangle) * sizeof(std::uint32_t)));
}

bool TexelRenderer::draw(int kind, const glm::mat4& viewProjection, int displayOrder, float exposure) {
  if (passOrder(kind) == 0) return false;
  const Pass& p = passes_[static_cast<std::size_t>(kind)];
  glBindVertexArray(vao_);
  // 1. Depth prepass: every triangle, depth only. The per-fragment PRT (order^2 bilinear
  // fetches per channel) is the expensive part; it must not run for fragments hidden later.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glUseProgram(depth_.id);
  glUniformMatrix4fv(depth_.viewProjection, 1, GL_FALSE, glm::value_ptr(viewProjection));
  glUniform1i(depth_.atlasSpace, 0);
  glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
  // 2. Shading: only the fragment that won the prepass passes EQUAL (invariant gl_Position),
  // each atlas's triangles with its texture array.
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_EQUAL);
  useShading(p, displayOrder, exposure, -1);
  glUniformMatrix4fv(shading_.viewProjection, 1, GL_FALSE, glm::value_ptr(viewProjection));
  for (std::size_t a = 0; a < atlases_.size(); ++a) {
    glBindTexture(GL_TEXTURE_2D_ARRAY, p.textures[a]);
    drawAtlas(a);
  }
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  return true;
}

Status TexelRenderer::readAtlas(int kind, int atlas, int displayOrder, std::vector<float>* out) {
  if (passOrder(kind) == 0) return Status::error(StatusCode::kInvalidArgument, "no texel pass of kind " + std::to_string(kind) + " on the GPU");
  if (atlas < 0 || static_cast<std::size_t>(atlas) >= atlases_.size()) {
    return Status::error(StatusCode::kInvalidArgument, "atlas " + std::to_string(atlas) + " out of range (the scene has " +
                                                           std::to_string(atlases_.size()) + ")");
  }
  const Pass& p = passes_[static_cast<std::size_t>(kind)];
  const TextureAtlas& a = atlases_[static_cast<std::size_t>(atlas)];
  const auto w = static_cast<GLsizei>(a.width), h = static_cast<GLsizei>(a.height);
  GLuint target = 0, framebuffer = 0;
  glGenTextures(1, &target);
  glBindTexture(GL_TEXTURE_2D, target);
  setNearestClamp(GL_TEXTURE_2D);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, w, h);
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target, 0);
  Status result = Status::ok();
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    result = Status::error(StatusCode::kInvalidArgument, "the atlas read-back needs float render targets (EXT_color_buffer_float)");
  } else {
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindVertexArray(vao_);
    useShading(p, displayOrder, 1.0f, atlas);
    glBindTexture(GL_TEXTURE_2D_ARRAY, p.textures[static_cast<std::size_t>(atlas)]);
    drawAtlas(static_cast<std::size_t>(atlas));
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    glBindVertexArray(0);
    out->assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, 0.0f);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, out->data());
    result = glErrorStatus("the atlas read-back", "reading an atlas back");
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(1, &target);
  glBindTexture(GL_TEXTURE_2D, 0);
  return result;
}

}  // namespace prt::web
