// GlRenderer's bi-scale part (docs/bi-scale.md, "The client"): per frame whose lighting
// changed, the glossy pass's table and transferred radiance T (gl_renderer.cpp) and T rotated
// into each vertex's tangent frame; per frame, the corners drawn with the RTT looked up and
// dotted per fragment.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bi_scale_texture.h"
#include "gl_program.h"
#include "gl_readback.h"
#include "gl_renderer.h"
#include "prt/rtt.h"
#include "rtt_texture.h"
#include "transfer_texture.h"
#include "web_shaders.h"

namespace prt::web {

void GlRenderer::releaseBiScale() {
  BiScalePass& b = biScale_;
  for (GLuint* t : {&b.rtt, &b.rotations, &b.rotated, &b.idMap, &b.placements})
    if (*t) glDeleteTextures(1, t);
  for (GLuint* buffer : {&b.rotatedBuffer, &b.corners})
    if (*buffer) glDeleteBuffers(1, buffer);
  if (b.vao) glDeleteVertexArrays(1, &b.vao);
  b = {};
}

Status GlRenderer::uploadBiScale(const BakedAsset& asset) {
  if (asset.rtt.empty()) {
    releaseBiScale();
    return Status::ok();
  }
  if (indexCount_ == 0 || asset.positions.size() != static_cast<std::size_t>(vertexCount_)) {
    return Status::error(StatusCode::kInvalidArgument, "uploadBiScale: no geometry, or another vertex count");
  }
  Rtt rtt;
  if (Status s = decodeRtt(asset.rtt, &rtt); !s.isOk()) return Status::error(s.code(), "the scene's RTT: " + s.message());
  GLint maxSize = 2048, maxLayers = 256;  // the WebGL2 minimums
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  RttTextures packed;
  PRT_RETURN_IF_ERROR(packRtt(rtt, maxSize, maxLayers, &packed));
  const int bands = std::min(rtt.order, asset.shOrder);
  BiScaleRotations rotations;
  PRT_RETURN_IF_ERROR(packBiScaleRotations(asset.normals, asset.tangents, bands, &rotations));
  int rotationRows = 0;
  PRT_RETURN_IF_ERROR(textureRowsFor(asset.positions.size() * static_cast<std::size_t>(rotations.texelsPerVertex), maxSize,
                                     "bi-scale rotations", &rotationRows));
  const bool perTriangle = !asset.idMap.empty() && asset.idMapPerTriangle;
  const bool synthesised = !asset.idMap.empty() && !perTriangle;  // over an atlas
  if (synthesised && asset.atlases.size() != 1) {
    return Status::error(StatusCode::kInvalidArgument, "the scene's synthesised id map spans " + std::to_string(asset.atlases.size()) +
                                                           " atlases; the client draws one");
  }
  std::vector<std::uint32_t> corners;
  PRT_RETURN_IF_ERROR(packBiScaleCorners(asset.positions, asset.normals, asset.tangents, asset.patchUv,
                                         synthesised ? std::span<const float>(asset.atlasUv) : std::span<const float>(),
                                         perTriangle ? std::span<const std::uint16_t>(asset.idMap) : std::span<const std::uint16_t>(),
                                         asset.indices, &corners));
  int placementRows = 0;
  std::vector<float> placementTexels;
  if (synthesised || perTriangle) {
    const std::vector<float> placements = packPatchPlacements(asset.patchPlacements);
    PRT_RETURN_IF_ERROR(textureRowsFor(placements.size() / 4, maxSize, "bi-scale patch placements", &placementRows));
    placementTexels.assign(static_cast<std::size_t>(kTransferTextureWidth) * placementRows * 4, 0.0f);
    std::copy(placements.begin(), placements.end(), placementTexels.begin());
    if (synthesised && (asset.atlases[0].width > static_cast<std::uint32_t>(maxSize) || asset.atlases[0].height > static_cast<std::uint32_t>(maxSize))) {
      return Status::error(StatusCode::kInvalidArgument, "the scene's id map is " + std::to_string(asset.atlases[0].width) + " x " +
                                                             std::to_string(asset.atlases[0].height) + " texels; this device holds " +
                                                             std::to_string(maxSize) + " a side");
    }
  }

  releaseBiScale();
  BiScalePass& b = biScale_;
  b.bands = bands;
  b.rttOrder = rtt.order;
  b.channels = rtt.channels;
  b.spatial = rtt.spatial;
  b.views = rtt.views;
  b.layersPerChannel = packed.layersPerChannel;
  b.rotationTexels = rotations.texelsPerVertex;
  glGenTextures(1, &b.rtt);
  glBindTexture(GL_TEXTURE_2D_ARRAY, b.rtt);
  // LINEAR blends the view samples of a block; the lookup never reaches across a block's edge.
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  const int layers = static_cast<int>(packed.halves.size() / (static_cast<std::size_t>(packed.size) * packed.size * 4));
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA16F, packed.size, packed.size, layers, 0, GL_RGBA, GL_HALF_FLOAT,
               packed.halves.data());
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  std::vector<float> rotationTexels(static_cast<std::size_t>(kTransferTextureWidth) * rotationRows * 4, 0.0f);
  std::copy(rotations.values.begin(), rotations.values.end(), rotationTexels.begin());
  glGenTextures(1, &b.rotations);
  glBindTexture(GL_TEXTURE_2D, b.rotations);
  setNearestClamp(GL_TEXTURE_2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTransferTextureWidth, rotationRows, 0, GL_RGBA, GL_FLOAT, rotationTexels.data());
  glBindTexture(GL_TEXTURE_2D, 0);
  b.perTriangle = perTriangle;
  if (synthesised || perTriangle) {
    glGenTextures(1, &b.placements);
    glBindTexture(GL_TEXTURE_2D, b.placements);
    setNearestClamp(GL_TEXTURE_2D);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTransferTextureWidth, placementRows, 0, GL_RGBA, GL_FLOAT, placementTexels.data());
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  if (synthesised) {
    b.idMapWidth = static_cast<int>(asset.atlases[0].width);
    b.idMapHeight = static_cast<int>(asset.atlases[0].height);
    glGenTextures(1, &b.idMap);
    glBindTexture(GL_TEXTURE_2D, b.idMap);
    setNearestClamp(GL_TEXTURE_2D);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R16UI, b.idMapWidth, b.idMapHeight, 0, GL_RED_INTEGER, GL_UNSIGNED_SHORT, asset.idMap.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glGenVertexArrays(1, &b.vao);
  glBindVertexArray(b.vao);
  b.corners = makeBuffer(GL_ARRAY_BUFFER, corners.data(), corners.size() * sizeof(std::uint32_t));
  constexpr GLsizei kStride = kBiScaleCornerWords * sizeof(std::uint32_t);
  const auto at = [](int word) { return reinterpret_cast<const void*>(static_cast<std::uintptr_t>(word) * sizeof(std::uint32_t)); };
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, kStride, at(0));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, kStride, at(3));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, kStride, at(6));
  glEnableVertexAttribArray(3);
  glVertexAttribPointer(3, 2, GL_FLOAT, GL_FALSE, kStride, at(9));
  glEnableVertexAttribArray(5);
  glVertexAttribPointer(5, 2, GL_FLOAT, GL_FALSE, kStride, at(11));
  glEnableVertexAttribArray(4);
  glVertexAttribIPointer(4, 3, GL_UNSIGNED_INT, kStride, at(13));
  glEnableVertexAttribArray(6);
  glVertexAttribIPointer(6, 1, GL_UNSIGNED_INT, kStride, at(16));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  b.cornerCount = static_cast<GLsizei>(asset.indices.size());
  if (Status s = glErrorStatus("this scene's bi-scale textures", "uploading the RTT"); !s.isOk()) {
    releaseBiScale();
    return s;
  }
  return Status::ok();
}

bool GlRenderer::updateBiScaleTransfer(GlossyPass& g, int kind, int bands, unsigned lightingVersion) {
  GlossyPrograms programs;
  if (!glossyPrograms(g, bands, &programs).isOk()) return false;
  BiScalePass& b = biScale_;
  if (glossyTableStale(g, lightingVersion, bands)) remakeGlossyTable(g, programs, lightingVersion, bands);
  if (!g.transferValid || !g.transferAll) {
    glossyTransfer(g, programs, true);
    g.transferValid = true;
    b.rotatedValid = false;
  }
  if (b.rotatedValid && b.rotatedBands == bands && b.rotatedKind == kind && b.rowTexels == g.rowTexels) return true;
  // The rotated T has T's layout: (re)made when the glossy pass's shape changed.
  if (!b.rotated || b.rowTexels != g.rowTexels || b.rotatedHeight != g.transferHeight) {
    if (b.rotated) glDeleteTextures(1, &b.rotated);
    if (b.rotatedBuffer) glDeleteBuffers(1, &b.rotatedBuffer);
    glGenTextures(1, &b.rotated);
    glBindTexture(GL_TEXTURE_2D, b.rotated);
    setNearestClamp(GL_TEXTURE_2D);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTransferTextureWidth, g.transferHeight, 0, GL_RGBA, GL_FLOAT, nullptr);
    glBindTexture(GL_TEXTURE_2D, 0);
    b.rotatedBuffer =
        makeBuffer(GL_ARRAY_BUFFER, nullptr, static_cast<std::size_t>(kTransferTextureWidth) * g.transferHeight * 4 * sizeof(float));
    // Unbound: WebGL refuses a draw capturing into a buffer that is bound elsewhere too.
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    b.rowTexels = g.rowTexels;
    b.rotatedHeight = g.transferHeight;
  }
  static const char* const kNames[16] = {"vR0", "vR1", "vR2",  "vR3",  "vR4",  "vR5",  "vR6",  "vR7",
                                         "vR8", "vR9", "vR10", "vR11", "vR12", "vR13", "vR14", "vR15"};
  const int rowTexels = g.rowTexels;
  const std::string defines = "#define BANDS " + std::to_string(bands) + "\n#define ROW_TEXELS " + std::to_string(rowTexels) + "\n";
  const Program* rotate = nullptr;
  if (!specialised("biscale-rotate", shaders::k_biscale_rotate_vert, defines, kNames, rowTexels, &rotate,
                   [=] { return biScaleRotateMain(bands, rowTexels); })
           .isOk()) {
    return false;
  }
  glUseProgram(rotate->id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, g.transfer);
  glUniform1i(rotate->transfer, 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, b.rotations);
  glUniform1i(rotate->rotations, 1);
  setTextureLayout(rotate->textureMask, rotate->textureShift);
  glUniform1i(rotate->vertices, vertexCount_);
  glBindVertexArray(tableVao_);  // no attributes: gl_VertexID alone
  const GLsizeiptr channelBytes = static_cast<GLsizeiptr>(vertexCount_) * rowTexels * 4 * static_cast<GLsizeiptr>(sizeof(float));
  for (int c = 0; c < 3; ++c) {
    glUniform1i(rotate->channel, c);
    capture(b.rotatedBuffer, vertexCount_, c * channelBytes, channelBytes);
  }
  copyBufferToTexture(b.rotatedBuffer, b.rotated, b.rotatedHeight);
  b.rotatedValid = true;
  b.rotatedBands = bands;
  b.rotatedKind = kind;
  return true;
}

bool GlRenderer::drawBiScale(const FrameParams& p) {
  BiScalePass& b = biScale_;
  if (!b.vao || !isPassKind(p.mode) || indexCount_ == 0) return false;
  GlossyPass& g = glossy_[static_cast<std::size_t>(p.mode)];
  if (g.bands == 0) return false;
  const int bands = std::clamp(std::min({p.displayOrder, g.bands, b.bands}), 1, 8);
  if (!updateBiScaleTransfer(g, static_cast<int>(p.mode), bands, p.lightingVersion)) return false;
  const bool synthesised = b.idMap != 0 || b.perTriangle;
  const std::string defines = "#define BANDS " + std::to_string(bands) + "\n#define ROW_TEXELS " + std::to_string(b.rowTexels) + "\n" +
                              (b.perTriangle ? "#define SYNTHESISED 2\n" : synthesised ? "#define SYNTHESISED 1\n" : "");
  const std::string key = "biscale-draw\n" + defines;
  auto it = specialised_.find(key);
  if (it == specialised_.end()) {
    Program program;
    if (Status st = link(shaders::k_biscale_vert, withDefines(shaders::k_biscale_frag, defines).c_str(), &program); !st.isOk()) {
      // Said once on the console (as an error: tests fail on it), then drawn as PRT.
      if (biScaleError_ != st.message()) std::fprintf(stderr, "prt: the bi-scale shader: %s\n", st.message().c_str());
      biScaleError_ = st.message();
      return false;
    }
    it = specialised_.emplace(key, program).first;
  }
  const Program& draw = it->second;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUseProgram(draw.id);
  glUniformMatrix4fv(draw.viewProjection, 1, GL_FALSE, &p.viewProjection[0][0]);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, b.rotated);
  glUniform1i(draw.rotated, 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, b.rtt);
  glUniform1i(draw.rtt, 1);
  setTextureLayout(draw.textureMask, draw.textureShift);
  glUniform1i(draw.vertices, vertexCount_);
  glUniform1i(draw.rttSpatial, b.spatial);
  glUniform1i(draw.rttViews, b.views);
  glUniform1i(draw.rttLayers, b.layersPerChannel);
  glUniform1i(draw.rttChannels, b.channels);
  glUniform1i(draw.viewDependent, p.viewDependent ? 1 : 0);
  glUniform3f(draw.eye, p.eye.x, p.eye.y, p.eye.z);
  glUniform1f(draw.exposure, p.exposure);
  if (synthesised) {
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, b.idMap);  // 0 for a per-triangle map (not sampled)
    glUniform1i(draw.idMap, 2);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, b.placements);
    glUniform1i(draw.placements, 3);
    glUniform2i(draw.idMapSize, b.idMapWidth, b.idMapHeight);
  }
  glBindVertexArray(b.vao);
  glDrawArrays(GL_TRIANGLES, 0, b.cornerCount);
  glBindVertexArray(0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  glActiveTexture(GL_TEXTURE0);
  return true;
}

std::vector<float> GlRenderer::readBiScaleRotated() const {
  const BiScalePass& b = biScale_;
  if (!b.rotatedBuffer || !b.rotatedValid) return {};
  std::vector<float> out(static_cast<std::size_t>(vertexCount_) * 3 * static_cast<std::size_t>(b.rowTexels) * 4);
  glBindBuffer(GL_ARRAY_BUFFER, b.rotatedBuffer);
  (void)readBoundBuffer(GL_ARRAY_BUFFER, out.size() * sizeof(float), out.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return out;
}

}  // namespace prt::web
