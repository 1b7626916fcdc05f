#include "gl_renderer.h"

#include <algorithm>
#include <string>
#include <vector>

#include "client_limits.h"
#include "gl_program.h"
#include "gl_readback.h"
#include "glossy_fused.h"
#include "lighting_block.h"
#include "transfer_texture.h"
#include "web_shaders.h"

namespace prt::web {
namespace {

// An integer RGBA texture of CPCA weight levels (8- or 16-bit, signed), nearest and clamped:
// the diffuse CPCA pass and the glossy pass store their per-vertex weights alike.
GLuint makeWeightTexture(int weightBits, int width, int height, const void* levels) {
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);
  setNearestClamp(GL_TEXTURE_2D);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (weightBits == 8) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8I, width, height, 0, GL_RGBA_INTEGER, GL_BYTE, levels);
  } else {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16I, width, height, 0, GL_RGBA_INTEGER, GL_SHORT, levels);
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  return t;
}

}  // namespace

Status GlRenderer::link(const char* vs, const char* fs, Program* out, const char* feedback) {
  return feedback ? link(vs, fs, out, &feedback, 1) : link(vs, fs, out, nullptr, 0);
}

Status GlRenderer::link(const char* vs, const char* fs, Program* out, const char* const* feedback, int count) {
  GLuint p = 0;
  if (Status s = linkProgram(vs, fs, &p, feedback, count); !s.isOk()) return s;
  bindUniformBlock(p, "Lighting", kLightingBlockBinding);
  out->id = p;
  out->viewProjection = glGetUniformLocation(p, "uViewProjection");
  out->inverseViewProjection = glGetUniformLocation(p, "uInverseViewProjection");
  out->backgroundMode = glGetUniformLocation(p, "uImage");
  out->environmentImage = glGetUniformLocation(p, "uEnvironmentImage");
  out->environmentRotation = glGetUniformLocation(p, "uEnvironmentRotation");
  out->environmentTint = glGetUniformLocation(p, "uEnvironmentTint");
  out->lightR = glGetUniformLocation(p, "uLightR");
  out->lightG = glGetUniformLocation(p, "uLightG");
  out->lightB = glGetUniformLocation(p, "uLightB");
  out->exposure = glGetUniformLocation(p, "uExposure");
  out->transfer = glGetUniformLocation(p, "uTransfer");
  out->textureMask = glGetUniformLocation(p, "uTextureMask");
  out->textureShift = glGetUniformLocation(p, "uTextureShift");
  out->texelsPerChannel = glGetUniformLocation(p, "uTexelsPerChannel");
  out->channels = glGetUniformLocation(p, "uChannels");
  out->activeTexels = glGetUniformLocation(p, "uActiveTexels");
  out->table = glGetUniformLocation(p, "uTable");
  out->weights = glGetUniformLocation(p, "uWeights");
  out->entries = glGetUniformLocation(p, "uEntries");
  out->weightTexels = glGetUniformLocation(p, "uWeightTexels");
  out->matrices = glGetUniformLocation(p, "uMatrices");
  out->rowTexels = glGetUniformLocation(p, "uRowTexels");
  out->matrixTexels = glGetUniformLocation(p, "uMatrixTexels");
  out->channel = glGetUniformLocation(p, "uChannel");
  out->vertices = glGetUniformLocation(p, "uVertices");
  out->fresnel = glGetUniformLocation(p, "uFresnel");
  out->eye = glGetUniformLocation(p, "uEye");
  out->shY00 = glGetUniformLocation(p, "uShY00");
  out->shK1 = glGetUniformLocation(p, "uShK1");
  out->shA = glGetUniformLocation(p, "uShA");
  out->shB = glGetUniformLocation(p, "uShB");
  out->vertexData = glGetUniformLocation(p, "uVertexData");
  out->fused = glGetUniformLocation(p, "uFused");
  out->allVertices = glGetUniformLocation(p, "uAllVertices");
  out->rotations = glGetUniformLocation(p, "uRotations");
  out->rotated = glGetUniformLocation(p, "uRotated");
  out->rtt = glGetUniformLocation(p, "uRtt");
  out->rttSpatial = glGetUniformLocation(p, "uRttSpatial");
  out->rttViews = glGetUniformLocation(p, "uRttViews");
  out->rttLayers = glGetUniformLocation(p, "uRttLayersPerChannel");
  out->rttChannels = glGetUniformLocation(p, "uRttChannels");
  out->viewDependent = glGetUniformLocation(p, "uViewDependent");
  out->idMap = glGetUniformLocation(p, "uIdMap");
  out->idMapSize = glGetUniformLocation(p, "uIdMapSize");
  out->placements = glGetUniformLocation(p, "uPlacements");
  return Status::ok();
}

Status GlRenderer::init() {
  if (Status s = link(shaders::k_prt_vert, shaders::k_discard_frag, &prt_, "vRadiance"); !s.isOk()) return s;
  if (Status s = link(shaders::k_radiance_vert, shaders::k_shade_frag, &radiance_); !s.isOk()) return s;
  if (Status s = link(shaders::k_cpca_vert, shaders::k_discard_frag, &cpca_, "vRadiance"); !s.isOk()) return s;
  glGenTransformFeedbacks(1, &feedback_);
  glGenVertexArrays(1, &tableVao_);
  if (Status s = link(shaders::k_lambert_vert, shaders::k_shade_frag, &lambert_); !s.isOk()) return s;
  if (Status s = link(shaders::k_background_vert, shaders::k_background_frag, &background_); !s.isOk()) return s;
  glGenVertexArrays(1, &backgroundVao_);
  return texels_.init();
}

void GlRenderer::releaseGeometry() {
  texels_.releaseGeometry();  // first: it draws from the buffers deleted below
  releaseBiScale();
  for (GLuint* b : {&positions_, &albedo_, &normals_, &indices_, &radianceBuffer_, &glossyBuffer_}) {
    if (*b) glDeleteBuffers(1, b);
    *b = 0;
  }
  for (GLuint* a : {&vao_, &feedbackVao_}) {
    if (*a) glDeleteVertexArrays(1, a);
    *a = 0;
  }
  vertexCount_ = 0;
  indexCount_ = 0;
}

void GlRenderer::releasePass(PassTexture* p) {
  for (GLuint* t : {&p->texture, &p->weights, &p->table})
    if (*t) glDeleteTextures(1, t);
  for (GLuint* b : {&p->tableBuffer, &p->clusterIds})
    if (*b) glDeleteBuffers(1, b);
  if (p->vao) glDeleteVertexArrays(1, &p->vao);
  *p = {};
}

void GlRenderer::releaseGlossy(GlossyPass* g) {
  for (GLuint* t : {&g->matrices, &g->weights, &g->table, &g->transfer, &g->vertexData, &g->fused})
    if (*t) glDeleteTextures(1, t);
  for (GLuint* b : {&g->tableBuffer, &g->transferBuffer, &g->clusterIds, &g->specular, &g->groupData, &g->fusedBuffer, &g->slots})
    if (*b) glDeleteBuffers(1, b);
  for (GLuint* a : {&g->vao, &g->fusedVao})
    if (*a) glDeleteVertexArrays(1, a);
  *g = {};
}

void GlRenderer::release() {
  releaseGeometry();
  for (PassTexture& t : passes_) releasePass(&t);
  for (GlossyPass& g : glossy_) releaseGlossy(&g);
}

void GlRenderer::setPassTexture(std::size_t kind, const TransferTexture& t, int order) {
  PassTexture& p = passes_[kind];
  if (p.cpca) releasePass(&p);
  if (!p.texture) glGenTextures(1, &p.texture);
  glBindTexture(GL_TEXTURE_2D, p.texture);
  setNearestClamp(GL_TEXTURE_2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, t.width, t.height, 0, GL_RGBA, GL_FLOAT, t.texels.data());
  p.channels = t.channels;
  p.texelsPerChannel = t.texelsPerChannel;
  p.order = order;
}

Status GlRenderer::uploadCpcaPass(TransferKind kind, const CpcaTransfer& cpca) {
  const auto k = static_cast<std::size_t>(kind);
  const int bands = static_cast<int>(cpca.bands.size());
  if (k > 2 || indexCount_ == 0 || bands < 1 || bands > bakedOrder_ || cpca.vertexCount != static_cast<std::uint32_t>(vertexCount_)) {
    return Status::error(StatusCode::kInvalidArgument, "uploadCpcaPass: no geometry, or pass kind, bands or vertex count out of range");
  }
  GLint maxSize = 2048;  // the WebGL2 minimum
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  CpcaTextures packed;
  if (Status s = packCpca(cpca, maxSize, &packed); !s.isOk()) return s;
  PassTexture& p = passes_[k];
  releasePass(&p);
  setPassTexture(k, packed.entries, bands);
  p.cpca = true;
  p.clusters = packed.clusters;
  p.entriesPerCluster = packed.entriesPerCluster;
  p.weightTexels = packed.weightTexels;
  p.weightsBefore = packed.weightsBefore;
  p.tableHeight = packed.tableHeight;
  p.weights = makeWeightTexture(packed.weightBits, packed.weightWidth, packed.weightHeight, packed.weightData.data());
  glGenTextures(1, &p.table);
  glBindTexture(GL_TEXTURE_2D, p.table);
  setNearestClamp(GL_TEXTURE_2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, packed.tableWidth, packed.tableHeight, 0, GL_RGB, GL_FLOAT, nullptr);
  glBindTexture(GL_TEXTURE_2D, 0);
  // Sized for the whole table texture: the copy reads every row (WebGL zero-fills buffers).
  p.tableBuffer = makeBuffer(GL_ARRAY_BUFFER, nullptr, static_cast<std::size_t>(packed.tableWidth) * packed.tableHeight * sizeof(Vec3));
  glGenVertexArrays(1, &p.vao);
  glBindVertexArray(p.vao);
  glBindBuffer(GL_ARRAY_BUFFER, albedo_);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Rgb), nullptr);
  p.clusterIds = makeBuffer(GL_ARRAY_BUFFER, packed.clusterOf.data(), packed.clusterOf.size() * sizeof(std::uint16_t));
  glEnableVertexAttribArray(4);
  glVertexAttribIPointer(4, 1, GL_UNSIGNED_SHORT, sizeof(std::uint16_t), nullptr);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  if (Status s = glErrorStatus("this scene's CPCA transfer", "uploading a CPCA pass"); !s.isOk()) {
    releasePass(&p);
    return s;
  }
  return Status::ok();
}

Status GlRenderer::uploadGlossyPass(TransferKind kind, const CpcaMatrixTransfer& cpca, std::span<const SpecularMaterial> specular,
                                    std::span<const Vec3> positions, std::span<const Vec3> normals) {
  const auto k = static_cast<std::size_t>(kind);
  if (k > 2 || indexCount_ == 0 || cpca.vertexCount != static_cast<std::uint32_t>(vertexCount_) ||
      positions.size() != cpca.vertexCount || normals.size() != cpca.vertexCount) {
    return Status::error(StatusCode::kInvalidArgument, "uploadGlossyPass: no geometry, or pass kind or vertex count out of range");
  }
  GLint maxSize = 2048;  // the WebGL2 minimum
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  GlossyTextures packed;
  if (Status s = packGlossy(cpca, specular, maxSize, &packed); !s.isOk()) return s;
  GlossyGroups groups;
  if (Status s = groupGlossyVertices(packed.clusterOf, packed.clusters, glossyGroupSize(packed.clusterOf.size(), static_cast<std::size_t>(packed.clusters), packed.vectors, packed.rowTexels), &groups); !s.isOk()) return s;
  const std::vector<float> vertexData = packGlossyVertexData(positions, normals, packed.specular);
  const std::size_t slotCount = groups.groups() * static_cast<std::size_t>(groups.size);
  int vertexDataHeight = 0, fusedHeight = 0;
  if (Status s = textureRowsFor(3 * positions.size(), maxSize, "glossy vertex data", &vertexDataHeight); !s.isOk()) return s;
  if (Status s = textureRowsFor(slotCount, maxSize, "glossy fused radiance", &fusedHeight); !s.isOk()) return s;
  GlossyPass& g = glossy_[k];
  releaseGlossy(&g);
  g.bands = packed.bands;
  g.channels = packed.channels;
  g.clusters = packed.clusters;
  g.vectors = packed.vectors;
  g.weightTexels = packed.weightTexels;
  g.matrixTexels = packed.matrixTexels;
  g.rowTexels = packed.rowTexels;
  g.tableTexels = packed.tableTexels;
  g.tableHeight = packed.tableHeight;
  g.transferHeight = packed.transferHeight;
  g.groups = static_cast<int>(groups.groups());
  g.groupSize = groups.size;
  g.fusedHeight = fusedHeight;
  // The programs of the packed order (the one displayed unless the order slider is lowered;
  // a lowered order links its own on first use).
  GlossyPrograms programs;
  if (Status s = glossyPrograms(g, g.bands, &programs); !s.isOk()) {
    releaseGlossy(&g);
    return s;
  }
  glGenTextures(1, &g.matrices);
  glBindTexture(GL_TEXTURE_2D, g.matrices);
  setNearestClamp(GL_TEXTURE_2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, packed.matrixWidth, packed.matrixHeight, 0, GL_RGBA, GL_FLOAT, packed.matrixData.data());
  g.weights = makeWeightTexture(packed.weightBits, packed.weightWidth, packed.weightHeight, packed.weightData.data());
  glGenTextures(1, &g.table);
  glBindTexture(GL_TEXTURE_2D, g.table);
  setNearestClamp(GL_TEXTURE_2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, packed.tableWidth, packed.tableHeight, 0, GL_RGBA, GL_FLOAT, nullptr);
  glBindTexture(GL_TEXTURE_2D, 0);
  // Sized for the whole table texture: the copy reads every row (WebGL zero-fills buffers).
  g.tableBuffer = makeBuffer(GL_ARRAY_BUFFER, nullptr, static_cast<std::size_t>(packed.tableWidth) * packed.tableHeight * 4 * sizeof(float));
  glGenTextures(1, &g.transfer);
  glBindTexture(GL_TEXTURE_2D, g.transfer);
  setNearestClamp(GL_TEXTURE_2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, packed.transferWidth, packed.transferHeight, 0, GL_RGBA, GL_FLOAT, nullptr);
  glBindTexture(GL_TEXTURE_2D, 0);
  g.transferBuffer =
      makeBuffer(GL_ARRAY_BUFFER, nullptr, static_cast<std::size_t>(packed.transferWidth) * packed.transferHeight * 4 * sizeof(float));
  glGenVertexArrays(1, &g.vao);
  glBindVertexArray(g.vao);
  glBindBuffer(GL_ARRAY_BUFFER, positions_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, normals_);
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
  g.clusterIds = makeBuffer(GL_ARRAY_BUFFER, packed.clusterOf.data(), packed.clusterOf.size() * sizeof(std::uint16_t));
  glEnableVertexAttribArray(4);
  glVertexAttribIPointer(4, 1, GL_UNSIGNED_SHORT, sizeof(std::uint16_t), nullptr);
  g.specular = makeBuffer(GL_ARRAY_BUFFER, packed.specular.data(), packed.specular.size() * sizeof(float));
  specularAttributePointers(static_cast<GLsizei>(kGlossySpecularFloats));
  g.slots = makeBuffer(GL_ARRAY_BUFFER, groups.slot.data(), groups.slot.size() * sizeof(std::uint32_t));
  glEnableVertexAttribArray(9);
  glVertexAttribIPointer(9, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t), nullptr);
  // The fused step's points: per group its cluster and kMaxGlossyGroup member ids.
  std::vector<std::int32_t> groupData(groups.groups() * (1 + kMaxGlossyGroup));
  for (std::size_t i = 0; i < groups.groups(); ++i) {
    groupData[i * (1 + kMaxGlossyGroup)] = static_cast<std::int32_t>(groups.cluster[i]);
    std::copy_n(&groups.members[i * kMaxGlossyGroup], kMaxGlossyGroup, &groupData[i * (1 + kMaxGlossyGroup) + 1]);
  }
  glGenVertexArrays(1, &g.fusedVao);
  glBindVertexArray(g.fusedVao);
  g.groupData = makeBuffer(GL_ARRAY_BUFFER, groupData.data(), groupData.size() * sizeof(std::int32_t));
  constexpr GLsizei kGroupStride = (1 + kMaxGlossyGroup) * sizeof(std::int32_t);
  glEnableVertexAttribArray(4);
  glVertexAttribIPointer(4, 1, GL_UNSIGNED_INT, kGroupStride, nullptr);
  glEnableVertexAttribArray(7);
  glVertexAttribIPointer(7, 4, GL_INT, kGroupStride, reinterpret_cast<const void*>(sizeof(std::int32_t)));
  glEnableVertexAttribArray(8);
  glVertexAttribIPointer(8, 4, GL_INT, kGroupStride, reinterpret_cast<const void*>(5 * sizeof(std::int32_t)));
  glBindVertexArray(0);
  std::vector<float> vertexTexels(static_cast<std::size_t>(kTransferTextureWidth) * vertexDataHeight * 4, 0.0f);
  std::copy(vertexData.begin(), vertexData.end(), vertexTexels.begin());
  glGenTextures(1, &g.vertexData);
  glBindTexture(GL_TEXTURE_2D, g.vertexData);
  setNearestClamp(GL_TEXTURE_2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTransferTextureWidth, vertexDataHeight, 0, GL_RGBA, GL_FLOAT, vertexTexels.data());
  glGenTextures(1, &g.fused);
  glBindTexture(GL_TEXTURE_2D, g.fused);
  setNearestClamp(GL_TEXTURE_2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTransferTextureWidth, fusedHeight, 0, GL_RGBA, GL_FLOAT, nullptr);
  glBindTexture(GL_TEXTURE_2D, 0);
  g.fusedBuffer = makeBuffer(GL_ARRAY_BUFFER, nullptr, static_cast<std::size_t>(kTransferTextureWidth) * fusedHeight * 4 * sizeof(float));
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  if (Status s = glErrorStatus("this scene's glossy transfer", "uploading a glossy pass"); !s.isOk()) {
    releaseGlossy(&g);
    return s;
  }
  return Status::ok();
}

int GlRenderer::glossyOrder(ShadingMode mode) const {
  if (!isPassKind(mode)) return 0;
  return glossy_[static_cast<std::size_t>(mode)].bands;
}

std::array<int, 3> GlRenderer::glossyShape(ShadingMode mode) const {
  if (glossyOrder(mode) == 0) return {0, 0, 0};
  const GlossyPass& g = glossy_[static_cast<std::size_t>(mode)];
  return {g.clusters, g.vectors, g.channels};
}

Status GlRenderer::glossyPrograms(const GlossyPass& g, int bands, GlossyPrograms* out) {
  if (bands < 1 || bands > g.bands || g.rowTexels < 1 || g.rowTexels > 16) {
    return Status::error(StatusCode::kInvalidArgument, "glossy pass: bad band count or row width");
  }
  static const char* const kNames[16] = {"vT0", "vT1", "vT2",  "vT3",  "vT4",  "vT5",  "vT6",  "vT7",
                                         "vT8", "vT9", "vT10", "vT11", "vT12", "vT13", "vT14", "vT15"};
  const std::string row = "#define ROW_TEXELS " + std::to_string(g.rowTexels) + "\n";
  const std::string table = row + "#define ROWS " + std::to_string(bands * bands) + "\n";
  const std::string transfer = row + "#define ACTIVE_TEXELS " + std::to_string(texelsForOrder(bands)) + "\n#define VECTORS " +
                               std::to_string(g.vectors) + "\n";
  const std::string view = "#define BANDS " + std::to_string(bands) + "\n";
  const std::string fused = view + "#define GROUP " + std::to_string(g.groupSize) + "\n" + row + "#define VECTORS " +
                            std::to_string(g.vectors) + "\n";
  static const char* const kTable = "vTable";
  static const char* const kGlossy = "vGlossy";
  static const char* const kFused[kMaxGlossyGroup] = {"vG0", "vG1", "vG2", "vG3", "vG4", "vG5", "vG6", "vG7"};
  PRT_RETURN_IF_ERROR(specialised("table", shaders::k_glossy_table_vert, table, &kTable, 1, &out->table));
  PRT_RETURN_IF_ERROR(specialised("transfer", shaders::k_glossy_transfer_vert, transfer, kNames, g.rowTexels, &out->transfer));
  PRT_RETURN_IF_ERROR(specialised("view", shaders::k_glossy_vert, view, &kGlossy, 1, &out->view));
  PRT_RETURN_IF_ERROR(specialised("gather", shaders::k_glossy_gather_vert, "", &kGlossy, 1, &out->gather));
  const int groupSize = g.groupSize, rowTexels = g.rowTexels, vectors = g.vectors;
  return specialised("fused", shaders::k_glossy_vert, fused, kFused, groupSize, &out->fused,
                     [=] { return glossyFusedMain(groupSize, bands, rowTexels, vectors); });
}

Status GlRenderer::specialised(const char* name, const char* vs, const std::string& defines, const char* const* feedback, int count,
                               const Program** out, const std::function<std::string()>& appendix) {
  const std::string key = std::string(name) + "\n" + defines;
  if (const auto it = specialised_.find(key); it != specialised_.end()) {
    *out = &it->second;
    return Status::ok();
  }
  Program p;
  const std::string source = withDefines(vs, defines) + (appendix ? appendix() : std::string());
  PRT_RETURN_IF_ERROR(link(source.c_str(), shaders::k_discard_frag, &p, feedback, count));
  *out = &specialised_.emplace(key, p).first->second;
  return Status::ok();
}

namespace {

// Binds a CPCA pass's table (unit 0) and weight levels (unit 1) for the bound program `p`,
// with the textures' layout and the weight texels a vertex: what the diffuse CPCA sum, the
// glossy transferred radiance and the fused step all read.
template <typename ProgramT, typename PassT>
void bindTableAndWeights(const ProgramT& p, const PassT& g) {
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, g.table);
  glUniform1i(p.table, 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, g.weights);
  glUniform1i(p.weights, 1);
  setTextureLayout(p.textureMask, p.textureShift);
  glUniform1i(p.weightTexels, g.weightTexels);
}

}  // namespace

void GlRenderer::glossyTable(GlossyPass& g, const GlossyPrograms& programs) {
  // Every cluster's (1 + N') matrices times the lighting, one point per texel.
  const Program& table = *programs.table;
  glUseProgram(table.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, g.matrices);
  glUniform1i(table.matrices, 0);
  setTextureLayout(table.textureMask, table.textureShift);
  glUniform1i(table.matrixTexels, g.matrixTexels);
  glUniform1i(table.channels, g.channels);
  glBindVertexArray(tableVao_);
  capture(g.tableBuffer, static_cast<GLsizei>(g.tableTexels));
  copyBufferToTexture(g.tableBuffer, g.table, g.tableHeight);
}

bool GlRenderer::glossyTableStale(const GlossyPass& g, unsigned lightingVersion, int bands) {
  return !g.tableValid || g.tableVersion != lightingVersion || g.tableBands != bands;
}

void GlRenderer::remakeGlossyTable(GlossyPass& g, const GlossyPrograms& programs, unsigned lightingVersion, int bands) {
  glossyTable(g, programs);
  g.tableValid = true;
  g.tableVersion = lightingVersion;
  g.tableBands = bands;
  g.transferValid = false;
}

void GlRenderer::glossyTransfer(GlossyPass& g, const GlossyPrograms& programs, bool allVertices) {
  // Per vertex and channel: the weighted sum of its cluster's table vectors, channel-major.
  const Program& t = *programs.transfer;
  glUseProgram(t.id);
  bindTableAndWeights(t, g);
  glUniform1i(t.allVertices, allVertices ? 1 : 0);
  g.transferAll = allVertices;
  glBindVertexArray(g.vao);
  const GLsizeiptr channelBytes = static_cast<GLsizeiptr>(vertexCount_) * g.rowTexels * 4 * static_cast<GLsizeiptr>(sizeof(float));
  for (int c = 0; c < 3; ++c) {
    glUniform1i(t.channel, c);
    capture(g.transferBuffer, vertexCount_, c * channelBytes, channelBytes);
  }
  copyBufferToTexture(g.transferBuffer, g.transfer, g.transferHeight);
}

namespace {

// The uniforms glossy.vert's lobe takes (both of its forms): the eye, Fresnel on or off and
// the SH recurrence's constants.
template <typename ProgramT>
void setLobeUniforms(const ProgramT& p, glm::vec3 eye, bool fresnel) {
  glUniform1i(p.fresnel, fresnel ? 1 : 0);
  glUniform3f(p.eye, eye.x, eye.y, eye.z);
  const ShRecurrenceConstants& sh = shRecurrenceConstants();
  glUniform1f(p.shY00, sh.y00);
  glUniform1f(p.shK1, sh.k1);
  glUniform4fv(p.shA, kMaxGlossyOrder * kMaxGlossyOrder / 4, sh.a);
  glUniform4fv(p.shB, kMaxGlossyOrder * kMaxGlossyOrder / 4, sh.b);
}

}  // namespace

void GlRenderer::glossyFused(GlossyPass& g, const GlossyPrograms& programs, glm::vec3 eye, bool fresnel) {
  // Per group of a cluster's vertices: their exit radiance straight from the table.
  const Program& f = *programs.fused;
  glUseProgram(f.id);
  bindTableAndWeights(f, g);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, g.vertexData);
  glUniform1i(f.vertexData, 2);
  setLobeUniforms(f, eye, fresnel);
  glBindVertexArray(g.fusedVao);
  capture(g.fusedBuffer, g.groups);
  copyBufferToTexture(g.fusedBuffer, g.fused, g.fusedHeight);
  // Back into vertex order, one fetch a vertex.
  const Program& gather = *programs.gather;
  glUseProgram(gather.id);
  glUniform1i(gather.fused, 0);
  setTextureLayout(gather.textureMask, gather.textureShift);
  glBindVertexArray(g.vao);
  capture(glossyBuffer_, vertexCount_);
  lastGlossyStep_ = "fused";
}

void GlRenderer::glossyView(GlossyPass& g, const GlossyPrograms& programs, glm::vec3 eye, bool fresnel) {
  // Per vertex: lobe convolution, y_i(R) toward the eye, Schlick, on the cached T.
  const Program& view = *programs.view;
  glUseProgram(view.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, g.transfer);
  glUniform1i(view.transfer, 0);
  setTextureLayout(view.textureMask, view.textureShift);
  glUniform1i(view.rowTexels, g.rowTexels);
  glUniform1i(view.vertices, vertexCount_);
  setLobeUniforms(view, eye, fresnel);
  glBindVertexArray(g.vao);
  capture(glossyBuffer_, vertexCount_);
  lastGlossyStep_ = "view";
}

bool GlRenderer::shadeGlossy(ShadingMode mode, int displayOrder, glm::vec3 eye, unsigned lightingVersion, bool fresnel,
                             GlossyWork work) {
  if (!isPassKind(mode) || indexCount_ == 0) return false;
  GlossyPass& g = glossy_[static_cast<std::size_t>(mode)];
  if (g.bands == 0) return false;
  const int bands = std::clamp(displayOrder, 1, g.bands);
  GlossyPrograms programs;
  if (!glossyPrograms(g, bands, &programs).isOk()) return false;
  const bool tableStale = glossyTableStale(g, lightingVersion, bands);
  const auto remakeTable = [&] { remakeGlossyTable(g, programs, lightingVersion, bands); };
  switch (work) {
    case GlossyWork::kTableOnly:
      remakeTable();
      return true;
    case GlossyWork::kRelight:
      remakeTable();
      glossyFused(g, programs, eye, fresnel);
      return true;
    case GlossyWork::kTransfer:
      remakeTable();
      glossyTransfer(g, programs);
      g.transferValid = true;
      glossyView(g, programs, eye, fresnel);
      return true;
    case GlossyWork::kViewOnly:
      if (!g.transferValid || tableStale) return false;
      glossyView(g, programs, eye, fresnel);
      return true;
    case GlossyWork::kAsNeeded:
      break;
  }
  // A frame whose lighting changed takes the fused step: it fetches each table texel once a
  // group, where T and the view step would fetch it once a vertex and then T again. While only
  // the camera moves, T (made once from the current table) and the view step cost less.
  if (tableStale) {
    remakeTable();
    glossyFused(g, programs, eye, fresnel);
    return true;
  }
  if (!g.transferValid) {
    glossyTransfer(g, programs);
    g.transferValid = true;
  }
  glossyView(g, programs, eye, fresnel);
  return true;
}

void GlRenderer::finishGlossy(ShadingMode mode, GlossyWork work) const {
  if (!isPassKind(mode) || glossy_[static_cast<std::size_t>(mode)].bands == 0) return;
  float value = 0.0f;
  glBindBuffer(GL_ARRAY_BUFFER, work == GlossyWork::kTableOnly ? glossy_[static_cast<std::size_t>(mode)].tableBuffer : glossyBuffer_);
  (void)readBoundBuffer(GL_ARRAY_BUFFER, sizeof(float), &value);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

std::vector<float> GlRenderer::readGlossy(std::size_t vertices) const {
  std::vector<float> out(std::min(vertices, static_cast<std::size_t>(vertexCount_)) * 3);
  if (out.empty()) return out;
  glBindBuffer(GL_ARRAY_BUFFER, glossyBuffer_);
  (void)readBoundBuffer(GL_ARRAY_BUFFER, out.size() * sizeof(float), out.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return out;
}

void GlRenderer::makeGeometry(const BakedAsset& asset) {
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  positions_ = makeBuffer(GL_ARRAY_BUFFER, asset.positions.data(), asset.positions.size() * sizeof(Vec3));
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
  albedo_ = makeBuffer(GL_ARRAY_BUFFER, asset.albedo.data(), asset.albedo.size() * sizeof(Rgb));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Rgb), nullptr);
  normals_ = makeBuffer(GL_ARRAY_BUFFER, asset.normals.data(), asset.normals.size() * sizeof(Vec3));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
  indices_ = makeBuffer(GL_ELEMENT_ARRAY_BUFFER, asset.indices.data(), asset.indices.size() * sizeof(std::uint32_t));
  radianceBuffer_ = makeBuffer(GL_ARRAY_BUFFER, nullptr, asset.positions.size() * sizeof(Vec3));
  glEnableVertexAttribArray(3);
  glVertexAttribPointer(3, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
  // Attribute 5, the glossy term: enabled by draw only while a glossy pass is drawn.
  glossyBuffer_ = makeBuffer(GL_ARRAY_BUFFER, nullptr, asset.positions.size() * sizeof(Vec3));
  glVertexAttribPointer(5, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
  glGenVertexArrays(1, &feedbackVao_);
  glBindVertexArray(feedbackVao_);
  glBindBuffer(GL_ARRAY_BUFFER, positions_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, albedo_);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Rgb), nullptr);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  vertexCount_ = static_cast<GLsizei>(asset.positions.size());
  indexCount_ = static_cast<GLsizei>(asset.indices.size());
  bakedOrder_ = asset.shOrder;
  texels_.setGeometry(positions_, albedo_, normals_, indices_, asset.atlasUv, asset.atlases);  // nothing without atlases
}

Status GlRenderer::uploadGeometry(const BakedAsset& asset) {
  release();
  makeGeometry(asset);
  return finishGeometry(asset);
}

Status GlRenderer::finishGeometry(const BakedAsset& asset) {
  Status s = glErrorStatus("this scene", "uploading the scene");
  // The glossy term's shading normals come with the geometry (the page fetches them with it).
  if (s.isOk()) s = texels_.setShadingNormals(asset.texelNormals, asset.texelCoverage);
  if (!s.isOk()) release();
  return s;
}

Status GlRenderer::uploadPass(const TransferPass& pass, int order) {
  const auto kind = static_cast<std::size_t>(pass.kind);
  if (kind > 2 || indexCount_ == 0 || order < 1 || order > bakedOrder_) {
    return Status::error(StatusCode::kInvalidArgument, "uploadPass: no geometry, or pass kind or order out of range");
  }
  GLint maxSize = 2048;  // the WebGL2 minimum
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  TransferTexture packed;
  if (Status s = packTransfer(pass, order, static_cast<std::size_t>(vertexCount_), maxSize, &packed); !s.isOk()) return s;
  setPassTexture(kind, packed, order);
  return glErrorStatus("this scene's transfer", "uploading a transfer pass");
}

Status GlRenderer::uploadTexelPass(const TransferPass& pass, int order) {
  if (pass.domain != TransferDomain::kTexel || indexCount_ == 0 || order < 1 || order > bakedOrder_) {
    return Status::error(StatusCode::kInvalidArgument, "uploadTexelPass: not a texel pass, no geometry, or an order out of range");
  }
  return texels_.uploadPass(pass, order);
}

int GlRenderer::texelOrder(ShadingMode mode) const { return isPassKind(mode) ? texels_.passOrder(static_cast<int>(mode)) : 0; }

Status GlRenderer::readTexelAtlas(ShadingMode mode, int atlas, const TexelShading& shading, std::vector<float>* out) {
  if (!isPassKind(mode)) return Status::error(StatusCode::kInvalidArgument, "readTexelAtlas: not a pass kind");
  return texels_.readAtlas(static_cast<int>(mode), atlas, shading, out);
}

int GlRenderer::passOrder(ShadingMode mode) const {
  if (!isPassKind(mode)) return 0;
  const PassTexture& t = passes_[static_cast<std::size_t>(mode)];
  return t.texture ? t.order : 0;
}

Status GlRenderer::upload(const BakedAsset& asset) {
  // Pack first: nothing on the GPU changes if a pass does not fit.
  GLint maxSize = 2048;  // the WebGL2 minimum
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  std::array<TransferTexture, 3> packed;
  for (const TransferPass& pass : asset.passes) {
    const auto kind = static_cast<std::size_t>(pass.kind);
    if (kind > 2 || pass.domain != TransferDomain::kVertex) continue;  // texel passes: uploadTexelPass
    if (Status s = packTransfer(pass, asset.shOrder, asset.positions.size(), maxSize, &packed[kind]); !s.isOk()) return s;
  }
  release();
  makeGeometry(asset);
  for (std::size_t k = 0; k < 3; ++k) {
    const TransferTexture& t = packed[k];
    if (t.texels.empty()) continue;
    setPassTexture(k, t, asset.shOrder);
  }
  return finishGeometry(asset);
}

bool GlRenderer::hasPass(ShadingMode mode) const {
  if (mode == ShadingMode::kLambert) return indexCount_ > 0;
  if (!isPassKind(mode)) return false;
  return passes_[static_cast<std::size_t>(mode)].texture != 0;
}

PassForm GlRenderer::passForm(ShadingMode mode) const {
  if (!isPassKind(mode) || !hasPass(mode)) return PassForm::kAbsent;
  return passes_[static_cast<std::size_t>(mode)].cpca ? PassForm::kCpca : PassForm::kExpanded;
}

std::array<int, 2> GlRenderer::cpcaShape(ShadingMode mode) const {
  if (passForm(mode) != PassForm::kCpca) return {0, 0};
  const PassTexture& t = passes_[static_cast<std::size_t>(mode)];
  return {t.clusters, t.weightsBefore.back()};
}

std::vector<float> GlRenderer::readRadiance(std::size_t vertices) const {
  std::vector<float> out(std::min(vertices, static_cast<std::size_t>(vertexCount_)) * 3);
  if (out.empty()) return out;
  glBindBuffer(GL_ARRAY_BUFFER, radianceBuffer_);
  (void)readBoundBuffer(GL_ARRAY_BUFFER, out.size() * sizeof(float), out.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return out;
}

void GlRenderer::capture(GLuint buffer, GLsizei points, GLintptr offset, GLsizeiptr bytes) {
  glEnable(GL_RASTERIZER_DISCARD);
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, feedback_);
  if (bytes > 0) {
    glBindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer, offset, bytes);
  } else {
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer);
  }
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, points);
  glEndTransformFeedback();
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
  glDisable(GL_RASTERIZER_DISCARD);
}

void GlRenderer::usePrtProgram(const PassTexture& t, int activeOrder) {
  glUseProgram(prt_.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, t.texture);
  glUniform1i(prt_.transfer, 0);
  setTextureLayout(prt_.textureMask, prt_.textureShift);
  glUniform1i(prt_.texelsPerChannel, t.texelsPerChannel);
  glUniform1i(prt_.channels, t.channels);
  glUniform1i(prt_.activeTexels, texelsForOrder(activeOrder));
}

void GlRenderer::shadeCpca(const PassTexture& t, int activeOrder) {
  // 1. The cluster table: prt.vert over the K * E entries (albedo 1), all in one pass;
  // per cluster and weight the lighting's dot product with the step-scaled axis.
  usePrtProgram(t, activeOrder);
  glBindVertexArray(tableVao_);
  glVertexAttrib3f(1, 1.0f, 1.0f, 1.0f);
  capture(t.tableBuffer, static_cast<GLsizei>(t.clusters * t.entriesPerCluster));
  // 2. Into the table texture, GPU to GPU.
  copyBufferToTexture(t.tableBuffer, t.table, t.tableHeight, GL_RGB);
  // 3. Per vertex: the cluster's constant plus the weighted sum of the displayed bands' weights.
  glUseProgram(cpca_.id);
  bindTableAndWeights(cpca_, t);
  glUniform1i(cpca_.entries, t.entriesPerCluster);
  glUniform1i(cpca_.activeTexels, (t.weightsBefore[static_cast<std::size_t>(activeOrder)] + 3) / 4);
  glUniform1i(cpca_.channels, t.channels);
  glBindVertexArray(t.vao);
  capture(radianceBuffer_, vertexCount_);
  glActiveTexture(GL_TEXTURE0);
}

bool GlRenderer::shade(ShadingMode mode, int displayOrder) {
  if (!isPassKind(mode) || indexCount_ == 0) return false;
  const PassTexture& t = passes_[static_cast<std::size_t>(mode)];
  if (!t.texture) return false;
  // PRT pass: prt.vert (or cpca.vert) runs once per vertex (points, rasteriser off) and its
  // exit radiance is captured by transform feedback. Shading every vertex exactly once
  // matters where vertices are not cached between triangles (software WebGL shades each
  // corner anew). A pass still streaming holds fewer bands than the asset: shade with those.
  const int activeOrder = std::clamp(std::min(displayOrder, t.order), 1, bakedOrder_);
  if (t.cpca) {
    shadeCpca(t, activeOrder);
  } else {
    usePrtProgram(t, activeOrder);
    glBindVertexArray(feedbackVao_);
    capture(radianceBuffer_, vertexCount_);
  }
  return true;
}

Status GlRenderer::setBackgroundImage(int width, int height, std::span<const std::uint32_t> texels) {
  if (texels.empty()) {
    if (backgroundImage_) glDeleteTextures(1, &backgroundImage_);
    backgroundImage_ = 0;
    return Status::ok();
  }
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (width < 1 || height < 1 || width > maxSize || height > maxSize) {
    return Status::error(StatusCode::kInvalidArgument, "background image " + std::to_string(width) + "x" + std::to_string(height) +
                                                           " is outside 1.." + std::to_string(maxSize) + " a side");
  }
  if (texels.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    return Status::error(StatusCode::kInvalidArgument, "background image: " + std::to_string(texels.size()) + " texels for " +
                                                           std::to_string(width) + "x" + std::to_string(height));
  }
  if (!backgroundImage_) glGenTextures(1, &backgroundImage_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, backgroundImage_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  // RGB9_E5 is filterable in every WebGL2 (GLES 3.0 core), unlike 32-bit floats.
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB9_E5, width, height, 0, GL_RGB, GL_UNSIGNED_INT_5_9_9_9_REV, texels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);  // no mipmaps: the map is magnified on screen
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);  // longitude wraps
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return Status::ok();
}

void GlRenderer::draw(int width, int height, const FrameParams& p) {
  glViewport(0, 0, width, height);
  if (p.background == BackgroundMode::kColour) {
    glClearColor(p.backgroundColour.r, p.backgroundColour.g, p.backgroundColour.b, 1.0f);
  } else {
    glClearColor(0.02f, 0.02f, 0.025f, 1.0f);
  }
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (p.background == BackgroundMode::kBlurred || p.background == BackgroundMode::kImage) {
    const bool image = p.background == BackgroundMode::kImage && backgroundImage_;
    glDisable(GL_DEPTH_TEST);
    glUseProgram(background_.id);
    const glm::mat4 inv = glm::inverse(p.viewProjection);
    glUniformMatrix4fv(background_.inverseViewProjection, 1, GL_FALSE, glm::value_ptr(inv));
    glUniform4fv(background_.lightR, kLightingTexelsPerChannel, p.environment);
    glUniform4fv(background_.lightG, kLightingTexelsPerChannel, p.environment + kMaxClientCoeffs);
    glUniform4fv(background_.lightB, kLightingTexelsPerChannel, p.environment + 2 * kMaxClientCoeffs);
    glUniform1f(background_.exposure, p.exposure);
    glUniform1i(background_.backgroundMode, image ? 1 : 0);
    glUniform1i(background_.environmentImage, 0);
    const glm::mat3 inverseRotation = glm::transpose(p.environmentRotation);  // the shader looks the map up at R^T d
    glUniformMatrix3fv(background_.environmentRotation, 1, GL_FALSE, glm::value_ptr(inverseRotation));
    glUniform3fv(background_.environmentTint, 1, glm::value_ptr(p.environmentTint));
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, image ? backgroundImage_ : 0);
    glBindVertexArray(backgroundVao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  if (indexCount_ == 0) return;
  if (p.mode == ShadingMode::kLambert) {
    glEnable(GL_DEPTH_TEST);
    glBindVertexArray(vao_);
    glUseProgram(lambert_.id);
    glUniformMatrix4fv(lambert_.viewProjection, 1, GL_FALSE, glm::value_ptr(p.viewProjection));
    glUniform1f(lambert_.exposure, p.exposure);  // lighting: the bound Lighting block
    glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
    return;
  }
  drewBiScale_ = p.biScale && drawBiScale(p);
  if (drewBiScale_) return;
  if (p.domain == TransferDomain::kTexel) {
    TexelShading shading;
    shading.displayOrder = p.displayOrder;
    shading.exposure = p.exposure;
    shading.diffuse = p.mix != GlossyMix::kGlossy;
    shading.glossy = p.mix != GlossyMix::kDiffuse;
    shading.eye = p.eye;
    shading.fresnel = p.fresnel;
    (void)texels_.draw(static_cast<int>(p.mode), p.viewProjection, shading);
    return;
  }
  // The terms of the pass: diffuse (vector pass) and glossy (matrix pass), each captured into
  // its buffer; a term switched off or absent is a constant zero attribute.
  const bool diffuse = p.mix != GlossyMix::kGlossy && shade(p.mode, p.displayOrder);
  const bool glossy = p.mix != GlossyMix::kDiffuse && shadeGlossy(p.mode, p.displayOrder, p.eye, p.lightingVersion, p.fresnel);
  if (!diffuse && !glossy) return;
  // Draw pass with the captured radiance.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindVertexArray(vao_);
  if (diffuse) {
    glEnableVertexAttribArray(3);
  } else {
    glDisableVertexAttribArray(3);
    glVertexAttrib3f(3, 0.0f, 0.0f, 0.0f);
  }
  if (glossy) {
    glEnableVertexAttribArray(5);
  } else {
    glDisableVertexAttribArray(5);
    glVertexAttrib3f(5, 0.0f, 0.0f, 0.0f);
  }
  glUseProgram(radiance_.id);
  glUniformMatrix4fv(radiance_.viewProjection, 1, GL_FALSE, glm::value_ptr(p.viewProjection));
  glUniform1f(radiance_.exposure, p.exposure);
  glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace prt::web
