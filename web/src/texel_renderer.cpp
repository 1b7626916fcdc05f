#include "texel_renderer.h"

#include <algorithm>
#include <string>

#include "gl_program.h"
#include "glossy_texture.h"
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
  out->diffuse = glGetUniformLocation(p, "uDiffuse");
  out->glossy = glGetUniformLocation(p, "uGlossy");
  out->visibility = glGetUniformLocation(p, "uVisibility");
  out->product = glGetUniformLocation(p, "uProduct");
  out->visibilityLayers = glGetUniformLocation(p, "uVisibilityLayers");
  out->bands = glGetUniformLocation(p, "uBands");
  out->fresnel = glGetUniformLocation(p, "uFresnel");
  out->eye = glGetUniformLocation(p, "uEye");
  out->writePosition = glGetUniformLocation(p, "uWritePosition");
  out->normals = glGetUniformLocation(p, "uNormals");
  out->shadingNormals = glGetUniformLocation(p, "uShadingNormals");
  out->shY00 = glGetUniformLocation(p, "uShY00");
  out->shK1 = glGetUniformLocation(p, "uShK1");
  out->shA = glGetUniformLocation(p, "uShA");
  out->shB = glGetUniformLocation(p, "uShB");
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
  releasePass(&visibility_);
  if (specular_) glDeleteBuffers(1, &specular_);
  if (productTexture_) glDeleteTextures(1, &productTexture_);
  specular_ = productTexture_ = 0;
  if (!normals_.empty()) glDeleteTextures(static_cast<GLsizei>(normals_.size()), normals_.data());
  normals_.clear();
  product_ = {};
  if (atlasUv_) glDeleteBuffers(1, &atlasUv_);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  atlasUv_ = 0;
  vao_ = 0;
  indexCount_ = 0;
  vertexCount_ = 0;
  atlases_.clear();
}

void TexelRenderer::setGeometry(GLuint positions, GLuint albedo, GLuint normals, GLuint indices, std::span<const float> atlasUv,
                                std::span<const TextureAtlas> atlases) {
  releaseGeometry();
  if (atlases.empty()) return;
  atlases_.assign(atlases.begin(), atlases.end());
  vertexCount_ = atlasUv.size() / 2;
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
  glBindBuffer(GL_ARRAY_BUFFER, normals);
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  // Attributes 5 and 6 (the specular material) stay constant zero until a visibility pass comes.
  glVertexAttrib4f(5, 0.0f, 0.0f, 0.0f, 0.0f);
  glVertexAttrib1f(6, 0.0f);
  glGenBuffers(1, &atlasUv_);
  glBindBuffer(GL_ARRAY_BUFFER, atlasUv_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(atlasUv.size() * sizeof(float)), atlasUv.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(7);
  glVertexAttribPointer(7, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

namespace {

// Packs `pass` and uploads one RGBA16F texture array per atlas into *out (GL names in
// out->textures); on error nothing is left on the GPU.
Status uploadArrays(const TransferPass& pass, int order, std::span<const TextureAtlas> atlases, std::vector<GLuint>* textures,
                    TexelTextures* shape) {
  GLint maxSize = 2048, maxLayers = 256;  // the WebGL2 minimums
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  // Pack first: nothing on the GPU changes if the pass does not fit.
  TexelTextures packed;
  if (Status s = packTexelTransfer(pass, order, atlases, maxSize, maxLayers, &packed); !s.isOk()) return s;
  std::vector<GLuint> names(packed.atlases.size(), 0);
  glGenTextures(static_cast<GLsizei>(names.size()), names.data());
  for (std::size_t a = 0; a < packed.atlases.size(); ++a) {
    const TexelAtlasTexture& t = packed.atlases[a];
    glBindTexture(GL_TEXTURE_2D_ARRAY, names[a]);
    // Bilinear within a layer (the dilated gutters keep the background out of it), no mipmaps.
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA16F, t.width, t.height, t.layers, 0, GL_RGBA, GL_HALF_FLOAT, t.halves.data());
  }
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  if (Status s = glErrorStatus("this scene's transfer textures", "uploading a texel pass"); !s.isOk()) {
    glDeleteTextures(static_cast<GLsizei>(names.size()), names.data());
    return s;
  }
  packed.atlases.clear();  // the halves are on the GPU now
  *textures = std::move(names);
  *shape = std::move(packed);
  return Status::ok();
}

}  // namespace

Status TexelRenderer::uploadPass(const TransferPass& pass, int order) {
  const auto kind = static_cast<std::size_t>(pass.kind);
  if (kind > 2 || atlases_.empty() || pass.form != TransferForm::kVector) {
    return Status::error(StatusCode::kInvalidArgument, "uploadTexelPass: no atlases, a pass kind out of range, or not a vector pass");
  }
  Pass next;
  TexelTextures shape;
  if (Status s = uploadArrays(pass, order, atlases_, &next.textures, &shape); !s.isOk()) return s;
  next.channels = shape.channels;
  next.order = shape.order;
  next.layersPerChannel = shape.layersPerChannel;
  releasePass(&passes_[kind]);
  passes_[kind] = std::move(next);
  return Status::ok();
}

Status TexelRenderer::uploadVisibility(const TransferPass& pass, int order, std::span<const SpecularMaterial> specular) {
  if (atlases_.empty() || pass.form != TransferForm::kVisibility || pass.channels != 1) {
    return Status::error(StatusCode::kInvalidArgument, "uploadVisibility: no atlases, or not a 1-channel visibility pass");
  }
  if (order < 1 || order > kMaxTripleTransferOrder) {
    return Status::error(StatusCode::kInvalidArgument, "the visibility pass holds " + std::to_string(order) +
                                                           " bands; the client reads at most " + std::to_string(kMaxTripleTransferOrder));
  }
  if (specular.size() != vertexCount_) {
    return Status::error(StatusCode::kInvalidArgument, "the asset has a visibility pass but " + std::to_string(specular.size()) +
                                                           " specular materials for " + std::to_string(vertexCount_) + " vertices");
  }
  Pass next;
  TexelTextures shape;
  if (Status s = uploadArrays(pass, order, atlases_, &next.textures, &shape); !s.isOk()) return s;
  next.channels = 1;
  next.order = shape.order;
  next.layersPerChannel = shape.layersPerChannel;
  std::vector<float> material(kGlossySpecularFloats * specular.size());
  for (std::size_t v = 0; v < specular.size(); ++v) {
    const SpecularMaterial& m = specular[v];
    float* dst = &material[kGlossySpecularFloats * v];
    dst[0] = m.f0.r;
    dst[1] = m.f0.g;
    dst[2] = m.f0.b;
    dst[3] = m.exponent;
    dst[4] = m.f90;
  }
  if (!specular_) glGenBuffers(1, &specular_);
  glBindBuffer(GL_ARRAY_BUFFER, specular_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(material.size() * sizeof(float)), material.data(), GL_STATIC_DRAW);
  glBindVertexArray(vao_);
  specularAttributePointers(static_cast<GLsizei>(kGlossySpecularFloats));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  releasePass(&visibility_);
  visibility_ = std::move(next);
  product_ = {};  // its transfer order may change with the visibility's
  return glErrorStatus("this scene's glossy transfer textures", "uploading the specular materials");
}

Status TexelRenderer::setProductLighting(std::span<const Rgb> lighting, int bands) {
  if (visibility_.order == 0) return Status::error(StatusCode::kInvalidArgument, "setProductLighting: no visibility pass");
  if (bands < 1 || bands > kMaxGlossyOrder) {
    return Status::error(StatusCode::kInvalidArgument, "TPFL product: " + std::to_string(bands) + " bands is not 1.." +
                                                           std::to_string(kMaxGlossyOrder));
  }
  const int transferOrder = tpflTransferOrder(bands, visibility_.order);
  if (tensor_.order() != bands || tensor_.transferOrder() != transferOrder) {
    if (Status s = ShTripleProduct::make(bands, transferOrder, &tensor_); !s.isOk()) return s;
  }
  TpflProductTexture next;
  if (Status s = packTpflProduct(tensor_, lighting, &next); !s.isOk()) return s;
  if (!productTexture_) glGenTextures(1, &productTexture_);
  glBindTexture(GL_TEXTURE_2D, productTexture_);
  setNearestClamp(GL_TEXTURE_2D);
  // A few hundred texels at most (57 x 192 at 8 bands): re-specified whole, every lighting change.
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, next.rowTexels, 3 * bands * bands, 0, GL_RGBA, GL_FLOAT, next.texels.data());
  glBindTexture(GL_TEXTURE_2D, 0);
  next.texels.clear();
  product_ = std::move(next);
  return glErrorStatus("the TPFL product matrix", "uploading the product matrix");
}

Status TexelRenderer::setShadingNormals(std::span<const std::int16_t> codes, std::span<const std::uint8_t> coverage) {
  if (codes.empty()) {
    if (!normals_.empty()) glDeleteTextures(static_cast<GLsizei>(normals_.size()), normals_.data());
    normals_.clear();
    return Status::ok();
  }
  if (atlases_.empty()) return Status::error(StatusCode::kInvalidArgument, "setShadingNormals: the scene has no atlases");
  GLint maxSize = 2048;  // the WebGL2 minimum
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  std::vector<TexelAtlasTexture> packed;
  if (Status s = packTexelNormals(codes, coverage, atlases_, maxSize, &packed); !s.isOk()) return s;
  std::vector<GLuint> names(packed.size(), 0);
  glGenTextures(static_cast<GLsizei>(names.size()), names.data());
  for (std::size_t a = 0; a < packed.size(); ++a) {
    glBindTexture(GL_TEXTURE_2D, names[a]);
    // Bilinear like the transfer (the baker dilated the normals into the gutters too).
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, packed[a].width, packed[a].height, 0, GL_RGBA, GL_HALF_FLOAT, packed[a].halves.data());
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  if (Status s = glErrorStatus("this scene's texel normals", "uploading the texel normals"); !s.isOk()) {
    glDeleteTextures(static_cast<GLsizei>(names.size()), names.data());
    return s;
  }
  if (!normals_.empty()) glDeleteTextures(static_cast<GLsizei>(normals_.size()), normals_.data());
  normals_ = std::move(names);
  return Status::ok();
}

int TexelRenderer::passOrder(int kind) const {
  if (kind < 0 || kind > 2) return 0;
  return passes_[static_cast<std::size_t>(kind)].order;
}

void TexelRenderer::useShading(const Pass& p, const TexelShading& shading, int atlas) {
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
  glUniform1i(shading_.activeLayers, texelsForOrder(std::clamp(std::min(shading.displayOrder, p.order), 1, p.order)));
  glUniform1f(shading_.exposure, shading.exposure);
  glUniform1i(shading_.diffuse, shading.diffuse ? 1 : 0);
  glUniform1i(shading_.writePosition, atlas >= 0 && shading.positions ? 1 : 0);
  const bool glossy = shading.glossy && glossyReady();
  glUniform1i(shading_.glossy, glossy ? 1 : 0);
  glUniform1i(shading_.visibility, 1);
  glUniform1i(shading_.product, 2);
  glUniform1i(shading_.normals, 3);
  glUniform1i(shading_.shadingNormals, glossy && !normals_.empty() ? 1 : 0);
  if (glossy) {
    // v past the product's transfer order cannot reach its first n bands (docs/triple-product.md).
    glUniform1i(shading_.visibilityLayers, texelsForOrder(std::min(visibility_.order, product_.transferOrder)));
    glUniform1i(shading_.bands, product_.bands);
    glUniform1i(shading_.fresnel, shading.fresnel ? 1 : 0);
    glUniform3f(shading_.eye, shading.eye.x, shading.eye.y, shading.eye.z);
    const ShRecurrenceConstants& sh = shRecurrenceConstants();
    glUniform1f(shading_.shY00, sh.y00);
    glUniform1f(shading_.shK1, sh.k1);
    glUniform4fv(shading_.shA, kMaxGlossyOrder * kMaxGlossyOrder / 4, sh.a);
    glUniform4fv(shading_.shB, kMaxGlossyOrder * kMaxGlossyOrder / 4, sh.b);
  }
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, glossy ? productTexture_ : 0);
  glActiveTexture(GL_TEXTURE0);
}

// Binds atlas `a`'s arrays: the diffuse pass's on unit 0, the visibility's on unit 1, and its
// shading normals on unit 3.
void TexelRenderer::bindAtlas(const Pass& p, std::size_t a) const {
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_2D, normals_.empty() ? 0 : normals_[a]);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, visibility_.order > 0 ? visibility_.textures[a] : 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, p.textures[a]);
}

void TexelRenderer::unbindTextures() const {
  for (GLenum unit : {GL_TEXTURE3, GL_TEXTURE2, GL_TEXTURE1, GL_TEXTURE0}) {
    glActiveTexture(unit);
    glBindTexture(unit == GL_TEXTURE2 || unit == GL_TEXTURE3 ? GL_TEXTURE_2D : GL_TEXTURE_2D_ARRAY, 0);
  }
}

void TexelRenderer::drawAtlas(std::size_t atlas) const {
  const TextureAtlas& a = atlases_[atlas];
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * a.triangleCount), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(static_cast<std::uintptr_t>(3u * a.firstTriangle) * sizeof(std::uint32_t)));
}

bool TexelRenderer::draw(int kind, const glm::mat4& viewProjection, const TexelShading& shading) {
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
  useShading(p, shading, -1);
  glUniformMatrix4fv(shading_.viewProjection, 1, GL_FALSE, glm::value_ptr(viewProjection));
  for (std::size_t a = 0; a < atlases_.size(); ++a) {
    bindAtlas(p, a);
    drawAtlas(a);
  }
  unbindTextures();
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  return true;
}

Status TexelRenderer::readAtlas(int kind, int atlas, const TexelShading& shading, std::vector<float>* out) {
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
    TexelShading linear = shading;
    linear.exposure = 1.0f;
    useShading(p, linear, atlas);
    bindAtlas(p, static_cast<std::size_t>(atlas));
    drawAtlas(static_cast<std::size_t>(atlas));
    unbindTextures();
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
