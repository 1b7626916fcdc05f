// WebGL2 drawing of a baked asset: geometry buffers, one transfer texture per pass, the PRT
// and Lambert programs and the SH background (emitters: dynamic_lighting.h; texel passes,
// transfer textures: texel_renderer.h). All GL in the project lives in web/.
#pragma once

#include <GLES3/gl3.h>

#include <array>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "cpca_texture.h"
#include "glossy_texture.h"
#include "glm_types.h"
#include "prt/asset.h"
#include "prt/status.h"
#include "texel_renderer.h"
#include "transfer_texture.h"

namespace prt::web {

// How the scene is shaded: one of the three transfer passes (whose values, as TransferKind's,
// are the pass kinds the client's API takes) or plain Lambert. Bound to JS as the embind
// enum ShadingMode (client_bindings.cpp): unshadowed, shadowed, interreflected, lambert.
enum class ShadingMode { kUnshadowed = 0, kShadowed = 1, kInterreflected = 2, kLambert = 3 };
// Whether `mode` names a transfer pass (not Lambert, and in range).
inline bool isPassKind(ShadingMode mode) {
  return mode == ShadingMode::kUnshadowed || mode == ShadingMode::kShadowed || mode == ShadingMode::kInterreflected;
}

// How a pass is drawn: absent, from expanded transfer, or straight from its CPCA clusters.
// Bound to JS as the embind enum PassForm: absent, expanded, cpca.
enum class PassForm { kAbsent = 0, kExpanded = 1, kCpca = 2 };

// Which terms of a pass are drawn (docs/web-client.md, "Glossy rendering"): the diffuse vector
// pass, the glossy matrix pass of the same kind, or their sum. Bound to JS as the embind enum
// GlossyMix: diffuse, glossy, both. A term whose pass the asset lacks draws as zero.
enum class GlossyMix { kDiffuse = 0, kGlossy = 1, kBoth = 2 };

// What is drawn behind the scene (docs/web-client.md, "Background"). Bound to JS as the
// embind enum BackgroundMode: none, colour, blurred, image.
enum class BackgroundMode {
  kNone = 0,     // the clear colour (near black)
  kColour = 1,   // a plain colour, FrameParams::backgroundColour
  kBlurred = 2,  // the SH lighting evaluated per pixel to order 4 (the light the scene gets)
  kImage = 3,    // the environment map itself (setBackgroundImage); kBlurred until one is set
};

struct FrameParams {
  glm::mat4 viewProjection{1.0f};
  ShadingMode mode = ShadingMode::kInterreflected;
  int displayOrder = 5;        // <= the baked order
  float exposure = 1.0f;       // linear multiplier
  BackgroundMode background = BackgroundMode::kImage;
  glm::vec3 backgroundColour{0.0f};  // kColour: display (sRGB) values in [0, 1], drawn as given
  // kImage: the environment's rotation R (the lighting is the map rotated, f'(u) = f(R^T u))
  // and its colour x intensity, as the SH lighting gets them.
  glm::mat3 environmentRotation{1.0f};
  glm::vec3 environmentTint{1.0f};
  // The environment alone (kPackedLightingFloats from packLighting) for the background. The PRT and
  // Lambert programs read the full lighting from the uniform block bound at
  // kLightingBlockBinding (lighting_block.h).
  const float* environment = nullptr;
  GlossyMix mix = GlossyMix::kBoth;
  glm::vec3 eye{0.0f};         // world-space camera position: the glossy term's view direction
  bool fresnel = true;         // Schlick's k_s (false: k_s = f0)
  // Changes whenever the bound lighting block may hold other values: the glossy pass keeps
  // its transferred radiance (view-independent) while this and the display order stay put.
  unsigned lightingVersion = 0;
  // Which pass of `mode` is drawn: the vertex pass (with its glossy term) or the texel pass
  // (transfer textures, with the TPFL glossy term; docs/web-client.md "Transfer textures").
  TransferDomain domain = TransferDomain::kVertex;
  // Bi-scale (docs/bi-scale.md): draw the scene per fragment with the asset's RTT over the glossy
  // matrix pass of `mode` (the macro scale) instead of the PRT terms, when the scene has both;
  // viewDependent false reads the RTT's centre view (the paper's Figure 6c).
  bool biScale = false;
  bool viewDependent = true;
};

// How much of the glossy work shadeGlossy does (docs/web-client.md, "Glossy rendering").
enum class GlossyWork {
  kAsNeeded = 0,   // lighting changed: table and fused step; else the view step (on T, made first if stale)
  kTableOnly = 1,  // the per-cluster table alone (benchmarks)
  kRelight = 2,    // table and fused step, as a frame whose lighting changed (benchmarks)
  kViewOnly = 3,   // the per-vertex view step alone, on the cached transferred radiance (benchmarks)
  kTransfer = 4,   // table, transferred radiance and view step (benchmarks; as kAsNeeded's first
                   // camera move after the lighting stopped changing, without the table)
};

class GlRenderer {
 public:
  // Compiles the programs; the WebGL2 context must be current.
  Status init();
  // Uploads geometry and every transfer pass of `asset`, replacing any previous scene.
  Status upload(const BakedAsset& asset);
  // The equirect environment image the kImage background samples (three.js mapping,
  // sh_project.h projectEquirect): width x height RGB9E5 texels, rows top first, as
  // UNSIGNED_INT_5_9_9_9_REV. Empty `texels` removes it. Fails naming the problem (a size
  // that does not match, over the GL limit) and keeps the previous image.
  Status setBackgroundImage(int width, int height, std::span<const std::uint32_t> texels);
  bool hasBackgroundImage() const { return backgroundImage_ != 0; }
  // Progressive loading: uploads the geometry of `asset` (its passes are ignored) and drops
  // every transfer pass; then uploadPass adds or replaces one pass, holding the first
  // `order` bands (order^2 coefficients per channel, <= the baked order). Until a pass is
  // uploaded its mode draws no scene. A pass that does not fit changes nothing.
  Status uploadGeometry(const BakedAsset& asset);
  Status uploadPass(const TransferPass& pass, int order);
  // Uploads pass `kind` in its CPCA form, rendered straight from the clusters (Sloan 2003;
  // cpca_texture.h), holding cpca.bands.size() bands; replaces either form of that pass. Like
  // uploadPass, needs geometry first, and a pass that does not fit changes nothing.
  Status uploadCpcaPass(TransferKind kind, const CpcaTransfer& cpca);
  // Uploads the glossy matrix pass `kind` (shadowed or interreflected) in its CPCA form
  // (glossy_texture.h), holding cpca.bands shells, with one specular material per vertex;
  // replaces a previous glossy pass of that kind. Needs geometry first; a pass that does not
  // fit changes nothing.
  // `positions` and `normals` are the geometry's (the fused step reads them a group at a time).
  Status uploadGlossyPass(TransferKind kind, const CpcaMatrixTransfer& cpca, std::span<const SpecularMaterial> specular,
                          std::span<const Vec3> positions, std::span<const Vec3> normals);
  // Bands the glossy pass of `mode` holds; 0 when absent (and for Lambert).
  int glossyOrder(ShadingMode mode) const;
  // Glossy pass of `mode`: {clusters, basis matrices per cluster, channels}; zeros when absent.
  std::array<int, 3> glossyShape(ShadingMode mode) const;
  // The glossy vertex passes alone for `mode` seen from `eye` with the bound lighting block
  // (version `lightingVersion`, FrameParams): the table and the transferred radiance when the
  // lighting or the display order changed since they were made (or as `work` forces), then the
  // per-vertex glossy radiance into the glossy buffer. False when the pass is absent.
  bool shadeGlossy(ShadingMode mode, int displayOrder, glm::vec3 eye, unsigned lightingVersion, bool fresnel = true,
                   GlossyWork work = GlossyWork::kAsNeeded);
  // Waits for the glossy passes queued so far: a 1-value read-back of the table buffer of
  // `mode` (kTableOnly) or of the glossy radiance buffer (benchmarks).
  void finishGlossy(ShadingMode mode, GlossyWork work) const;
  // Which step wrote the glossy radiance last: "fused" (a frame whose lighting changed),
  // "view" (on the cached transferred radiance) or "" (none yet). Tests check both.
  const char* lastGlossyStep() const { return lastGlossyStep_; }
  // The glossy radiance the last frame computed, RGB per vertex (synchronous read-back).
  std::vector<float> readGlossy(std::size_t vertices) const;
  int passOrder(ShadingMode mode) const;  // bands the uploaded pass holds; 0 when absent
  // Uploads texel pass `pass` (domain kTexel) holding `order` bands (<= the baked order) into
  // transfer textures, replacing the texel pass of its kind. Needs geometry with atlases; a
  // pass that does not fit changes nothing.
  Status uploadTexelPass(const TransferPass& pass, int order);
  // Bands the texel pass of `mode` holds; 0 when absent (and for Lambert).
  int texelOrder(ShadingMode mode) const;
  // The scene's atlases (empty without transfer textures).
  const std::vector<TextureAtlas>& atlases() const { return texels_.atlases(); }
  // The TPFL visibility pass and the per-vertex specular materials (TexelRenderer::uploadVisibility).
  Status uploadTexelVisibility(const TransferPass& pass, int order, std::span<const SpecularMaterial> specular) {
    return texels_.uploadVisibility(pass, order, specular);
  }
  int texelVisibilityOrder() const { return texels_.visibilityOrder(); }  // 0 when absent
  // P_c(L) for the texel glossy term from `lighting` (bands^2 RGB; TexelRenderer::setProductLighting).
  Status setTexelProduct(std::span<const Rgb> lighting, int bands) { return texels_.setProductLighting(lighting, bands); }
  // Atlas `atlas` of texel pass `mode` rendered in UV space and read back as linear RGBA
  // floats (TexelRenderer::readAtlas), with the bound lighting block and `shading`'s terms.
  Status readTexelAtlas(ShadingMode mode, int atlas, const TexelShading& shading, std::vector<float>* out);
  bool hasPass(ShadingMode mode) const;
  // How pass `mode` is drawn (kAbsent for Lambert).
  PassForm passForm(ShadingMode mode) const;
  // CPCA pass `mode`: {clusters, weights per vertex at its bands}; {0, 0} otherwise.
  std::array<int, 2> cpcaShape(ShadingMode mode) const;
  void draw(int width, int height, const FrameParams& p);
  // The PRT vertex pass alone (exit radiance of every vertex into the radiance buffer, with
  // the bound lighting block), as draw runs it; false when `mode` has no pass (or is Lambert).
  bool shade(ShadingMode mode, int displayOrder);
  // The exit radiance the last PRT frame computed, RGB per vertex, of the first `vertices`
  // (at most all; synchronous read-back, so it also waits for the PRT pass: tests and
  // benchmarks only). Empty without geometry.
  std::vector<float> readRadiance(std::size_t vertices) const;
  // Bi-scale (docs/bi-scale.md, "The client"): uploads the asset's RTT (packRtt), the
  // per-vertex SH rotations into its tangent frames and the de-indexed corners; an asset
  // without an RTT drops any previous one. Needs geometry first. Nothing changes on failure.
  Status uploadBiScale(const BakedAsset& asset);
  // Bands bi-scale can shade: the RTT's order, at most the asset's; 0 without an RTT.
  int biScaleOrder() const { return biScale_.bands; }
  // The last frame drew bi-scale (FrameParams::biScale with an RTT and a glossy pass of its mode).
  bool drewBiScale() const { return drewBiScale_; }
  // Tests: the rotated transferred radiance of the last bi-scale frame, [channel][vertex][row
  // texels * 4] (synchronous read-back); empty before one.
  std::vector<float> readBiScaleRotated() const;
  int biScaleRowTexels() const { return biScale_.rowTexels; }

 private:

  struct Program {
    GLuint id = 0;
    GLint viewProjection = -1, lightR = -1, lightG = -1, lightB = -1, exposure = -1;
    GLint transfer = -1, textureMask = -1, textureShift = -1, texelsPerChannel = -1, channels = -1, activeTexels = -1;
    GLint inverseViewProjection = -1;
    GLint table = -1, weights = -1, entries = -1, weightTexels = -1;
    // glossy_table.vert, glossy.vert
    GLint matrices = -1, rowTexels = -1, matrixTexels = -1;
    GLint channel = -1, vertices = -1;
    GLint fresnel = -1, eye = -1, shY00 = -1, shK1 = -1, shA = -1, shB = -1;
    GLint vertexData = -1, fused = -1;  // glossy.vert's fused form, glossy_gather.vert
    GLint allVertices = -1;  // glossy_transfer.vert
    // biscale_rotate.vert, biscale.frag
    GLint rotations = -1, rotated = -1, rtt = -1, rttSpatial = -1, rttViews = -1, rttLayers = -1, rttChannels = -1;
    GLint viewDependent = -1, idMap = -1, idMapSize = -1, placements = -1;
    // background.frag
    GLint backgroundMode = -1, environmentImage = -1, environmentRotation = -1, environmentTint = -1;
  };
  // A glossy matrix pass in its CPCA form (glossy_texture.h): matrices, weight levels, the
  // table and the transferred radiance (each captured into its buffer, copied into its
  // texture) with the lighting version and bands they were made for, and a VAO feeding
  // glossy_transfer.vert and glossy.vert (position, normal, cluster id, specular material).
  // The fused step (glossy_fused.h) reads the vertices a group at a time (groupData, fusedVao:
  // cluster and members per group; vertexData: position, normal, material per vertex), captures
  // one vec4 per group slot (fusedBuffer, copied into `fused`), which glossy_gather.vert reads
  // back into vertex order by each vertex's slot (slots, attribute 9 of vao).
  struct GlossyPass {
    GLuint matrices = 0, weights = 0, table = 0, tableBuffer = 0, transfer = 0, transferBuffer = 0;
    GLuint clusterIds = 0, specular = 0, vao = 0;
    GLuint groupData = 0, fusedVao = 0, vertexData = 0, fusedBuffer = 0, fused = 0, slots = 0;
    int bands = 0, channels = 0, clusters = 0, vectors = 0, weightTexels = 0, matrixTexels = 0, rowTexels = 0;
    int tableTexels = 0, tableHeight = 0, transferHeight = 0;
    int groups = 0, groupSize = 0, fusedHeight = 0;
    // The table holds the lighting of tableVersion at tableBands when tableValid; T was made
    // from that table when transferValid.
    bool tableValid = false, transferValid = false;
    bool transferAll = false;  // T was made for every vertex (bi-scale), not only the glossy ones
    unsigned tableVersion = 0;
    int tableBands = 0;
  };
  static void releaseGlossy(GlossyPass* g);
  struct PassTexture {
    GLuint texture = 0;  // the transfer, or for CPCA the cluster entries (both packTransfer layout)
    int channels = 0, texelsPerChannel = 0;
    int order = 0;  // bands held: the baked order, or fewer while streaming
    // CPCA form (cpca_texture.h): integer weight levels, the per-frame table (captured into
    // tableBuffer, copied into the table texture), cluster ids as a vertex attribute in vao.
    bool cpca = false;
    GLuint weights = 0, table = 0, tableBuffer = 0, clusterIds = 0, vao = 0;
    int clusters = 0, entriesPerCluster = 0, weightTexels = 0, tableHeight = 0;
    std::vector<int> weightsBefore;
  };
  // `feedback`: name of a varying to capture with transform feedback, or nullptr.
  Status link(const char* vs, const char* fs, Program* out, const char* feedback = nullptr);
  // The same with `count` varyings captured interleaved.
  Status link(const char* vs, const char* fs, Program* out, const char* const* feedback, int count);
  // The three glossy programs for a pass at a displayed band count, each linked with its
  // compile-time shape (docs/web-client.md, "Glossy rendering").
  struct GlossyPrograms {
    const Program* table = nullptr;     // glossy_table.vert: ROW_TEXELS, ROWS
    const Program* transfer = nullptr;  // glossy_transfer.vert: ROW_TEXELS, ACTIVE_TEXELS, VECTORS
    const Program* view = nullptr;      // glossy.vert: BANDS
    const Program* fused = nullptr;     // glossy.vert + glossyFusedMain: BANDS, GROUP
    const Program* gather = nullptr;    // glossy_gather.vert
  };
  // Links (once per shape, kept for the context's life) and returns the programs of pass `g`
  // at `bands` (1 .. g.bands).
  Status glossyPrograms(const GlossyPass& g, int bands, GlossyPrograms* out);
  // `vs` with `defines` after its version line (and `appendix()` after its end, when given),
  // linked once per (name, defines) into specialised_, capturing `count` varyings of `feedback`
  // (interleaved when more than one). The defines must determine the appendix.
  Status specialised(const char* name, const char* vs, const std::string& defines, const char* const* feedback, int count,
                     const Program** out, const std::function<std::string()>& appendix = {});
  // The glossy steps of `g` for the bound lighting (docs/web-client.md, "Glossy rendering"):
  // the per-cluster table; T from the table; the fused step (exit radiance toward `eye`
  // straight from the table, into the glossy buffer); the view step (the same from T).
  void glossyTable(GlossyPass& g, const GlossyPrograms& programs);
  // Whether g's table holds another lighting version or band count than asked; the table
  // remade for them (T then stale).
  static bool glossyTableStale(const GlossyPass& g, unsigned lightingVersion, int bands);
  void remakeGlossyTable(GlossyPass& g, const GlossyPrograms& programs, unsigned lightingVersion, int bands);
  // allVertices: T of matte vertices too (bi-scale reads every vertex's; glossy.vert skips them).
  void glossyTransfer(GlossyPass& g, const GlossyPrograms& programs, bool allVertices = false);
  void glossyFused(GlossyPass& g, const GlossyPrograms& programs, glm::vec3 eye, bool fresnel);
  void glossyView(GlossyPass& g, const GlossyPrograms& programs, glm::vec3 eye, bool fresnel);
  void release();
  void releaseGeometry();
  void makeGeometry(const BakedAsset& asset);  // buffers and VAOs; the caller checks for GL errors
  // After makeGeometry (and any pass textures): the GL error check, then the texel shading
  // normals, which come with the geometry. On failure everything is released.
  Status finishGeometry(const BakedAsset& asset);
  // Replaces the texture of pass `kind` with `t` (packed at `order`), dropping a CPCA form.
  void setPassTexture(std::size_t kind, const TransferTexture& t, int order);
  static void releasePass(PassTexture* p);
  // Runs the bound program once per point over `points` points of the bound VAO, rasteriser
  // off, capturing its output into `buffer` (from byte `offset`, `bytes` long; 0: all of it)
  // by transform feedback.
  void capture(GLuint buffer, GLsizei points, GLintptr offset = 0, GLsizeiptr bytes = 0);
  // prt.vert in use over pass texture `t` (transfer or CPCA entries), shading `activeOrder` bands.
  void usePrtProgram(const PassTexture& t, int activeOrder);
  // The PRT vertex pass of a CPCA pass: the table, then the per-vertex weighted sums.
  void shadeCpca(const PassTexture& t, int activeOrder);

  // Bi-scale's GPU state (gl_renderer_bi_scale.cpp): the RTT texture array, the per-vertex
  // rotations, the rotated transferred radiance (captured into rotatedBuffer, copied into
  // `rotated`, in T's layout) and the corners' VAO; rotatedValid while it holds the table of
  // its glossy pass at rotatedBands.
  struct BiScalePass {
    GLuint rtt = 0, rotations = 0, rotated = 0, rotatedBuffer = 0, corners = 0, vao = 0;
    GLuint idMap = 0, placements = 0;  // the synthesised id map (R16UI over the atlas) and its placements
    int idMapWidth = 0, idMapHeight = 0;  // 0: parametric (patch uv), or per triangle
    bool perTriangle = false;             // the id map is per triangle (in the corners)
    int bands = 0, rttOrder = 0, channels = 0, spatial = 0, views = 0, layersPerChannel = 0;
    int rotationTexels = 0, rowTexels = 0, rotatedHeight = 0;
    GLsizei cornerCount = 0;
    bool rotatedValid = false;
    int rotatedBands = 0, rotatedKind = -1;
  };
  void releaseBiScale();
  // The bi-scale draw of FrameParams `p` (after the background); false when it cannot (no RTT,
  // no glossy pass of p.mode), so the caller draws PRT instead.
  bool drawBiScale(const FrameParams& p);
  // Remakes the glossy table and T (every vertex) of `g` when stale, then the rotated T at `bands`.
  bool updateBiScaleTransfer(GlossyPass& g, int kind, int bands, unsigned lightingVersion);

  Program prt_, lambert_, background_, radiance_, cpca_;
  std::map<std::string, Program> specialised_;  // the glossy programs by shape (specialised())
  GLuint tableVao_ = 0;  // no arrays: the table pass reads only gl_VertexID (albedo constant 1)
  // vao_ draws triangles (position, albedo, normal, radiance); feedbackVao_ feeds the PRT
  // pass (position, albedo) without the radiance buffer it writes, as WebGL2 requires.
  GLuint vao_ = 0, feedbackVao_ = 0, positions_ = 0, albedo_ = 0, normals_ = 0, indices_ = 0, radianceBuffer_ = 0;
  const char* lastGlossyStep_ = "";
  GLuint glossyBuffer_ = 0;  // glossy radiance per vertex (attribute 5 of vao_)
  GLuint backgroundVao_ = 0, feedback_ = 0, backgroundImage_ = 0;
  GLsizei vertexCount_ = 0;
  GLsizei indexCount_ = 0;
  int bakedOrder_ = 0;
  std::array<PassTexture, 3> passes_{};
  std::array<GlossyPass, 3> glossy_{};  // by TransferKind (unshadowed unused: no such matrix pass is baked)
  TexelRenderer texels_;
  BiScalePass biScale_;
  bool drewBiScale_ = false;
  std::string biScaleError_;  // the last bi-scale program that failed to link, said once  // texel passes, drawn from this class's position, albedo and index buffers
};

}  // namespace prt::web
