// The client's state and per-frame work, driven from JavaScript through embind
// (client_bindings.cpp): the decoded scene on the GPU, the lighting (an environment's SH
// or a constant "white furnace", its live rotation by the shared SH rotation, plus dynamic
// area lights projected through a light cube map: dynamic_lighting.h), and the orbit camera
// (orbit_camera.h).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "asset_stream.h"
#include "client_limits.h"
#include "dynamic_lighting.h"
#include "gl_context.h"
#include "gl_renderer.h"
#include "glm_types.h"
#include "orbit_camera.h"
#include "prt/asset.h"
#include "prt/vec3.h"

namespace prt::web {

class ClientApp {
 public:
  // Creates the GL context (gl_context.h: WebGL2 on the canvas `options.canvas` in the
  // browser, an off-screen OpenGL ES 3 context natively). On failure error() says why
  // (WebGL2 missing) and every other call is a no-op.
  explicit ClientApp(const GlContextOptions& options);
  const std::string& error() const { return error_; }

  // Memory JS streams the asset into (no extra copy): call with the byte count, fill it,
  // then loadAsset(). Returns nullptr when `bytes` cannot be allocated.
  std::uint8_t* reserveAsset(std::size_t bytes);
  // Decodes the reserved bytes with the shared reader and uploads them. Returns "" or the
  // error (named by the reader: truncated, checksum mismatch, ...). Frames the camera.
  std::string loadAsset();

  // ---- progressive loading (docs/web-client.md, "Progressive loading") ----
  // A zeroed buffer of the catalogue's file size for the parts (nullptr when it cannot be
  // allocated); streamBuffer() is the same memory, to re-take after memory growth.
  std::uint8_t* reserveStream(std::size_t bytes);
  std::uint8_t* streamBuffer() { return stream_.data(); }
  std::size_t streamSize() const { return stream_.size(); }
  // Once the head and every non-transfer section are in the buffer: validates and decodes
  // the geometry, uploads it without transfer, frames the camera and picks the displayed
  // pass (mode()). "" or the reader's error.
  std::string streamGeometry();
  // Decodes pass `kind` (a ShadingMode with a pass: isPassKind) from its first `bands` bands
  // (0: all; float32 passes only decode whole) and re-uploads it at that order. "" or the
  // error; bands checked by their CRCs.
  std::string streamPass(ShadingMode kind, int bands);
  // Frees the stream buffer once every part has been applied (or on failure).
  void endStream() { stream_.release(); }
  // Bands of pass `kind` on the GPU (0 when absent, and for Lambert): the baked order once
  // loaded whole.
  int loadedBands(ShadingMode kind) const { return renderer_.passOrder(kind); }

  // ---- CPCA rendering (docs/web-client.md, "CPCA rendering") ----
  // Whether CPCA-encoded passes are rendered straight from the clusters (Sloan 2003; the
  // default) or expanded to plain transfer first. Applies to passes loaded afterwards.
  void setCpcaDirect(bool on) { cpcaDirect_ = on; }
  bool cpcaDirect() const { return cpcaDirect_; }
  // How pass `kind` is drawn (absent for Lambert).
  PassForm passForm(ShadingMode kind) const { return renderer_.passForm(kind); }
  // CPCA pass `kind`: [clusters, weights per vertex]; [0, 0] otherwise.
  std::vector<int> cpcaShape(ShadingMode kind) const {
    const auto s = renderer_.cpcaShape(kind);
    return {s[0], s[1]};
  }
  // Exit radiance of every vertex in the last frame, flat RGB before exposure (reads the
  // GPU buffer back: tests and tools only).
  std::vector<float> vertexRadiance() const;

  // ---- transfer textures (docs/web-client.md, "Transfer textures") ----
  // Draws the passes of domain `d`: per vertex (kVertex, the default) or per texel (kTexel).
  // Kept as the wish: a scene without passes of `d` is drawn from its other domain (a
  // texel-only asset from its texel passes), and the next scene that has them honours it.
  void setSource(TransferDomain d);
  // The domain drawn now.
  TransferDomain source() const { return source_; }
  // Whether the scene has (or is streaming) passes of domain `d`.
  bool hasSource(TransferDomain d) const;
  // Decodes texel pass `kind` from its first `bands` bands (0: all; float32 passes only
  // decode whole) and re-uploads it as transfer textures at that order. "" or the error.
  std::string streamTexelPass(ShadingMode kind, int bands);
  // Bands of texel pass `kind` on the GPU (0 when absent, and for Lambert).
  int texelBands(ShadingMode kind) const { return renderer_.texelOrder(kind); }
  // Decodes the TPFL visibility pass from its first `bands` bands (0: all; float32 passes only
  // decode whole) and uploads it as the texel passes' glossy term. "" or the error.
  std::string streamVisibilityPass(int bands);
  // Whether the scene has (or is streaming) a TPFL visibility pass: the texel glossy term.
  bool hasTexelGlossy() const;
  // Bands of the visibility pass on the GPU (0 when absent).
  int texelGlossyBands() const { return renderer_.texelVisibilityOrder(); }
  // The last failure to remake the texel glossy term's product matrix ("" when none).
  std::string texelGlossyError() const { return productError_; }
  // The atlases' sizes, [width0, height0, width1, height1, ...] (empty without texel passes).
  std::vector<int> atlasSizes() const;
  // Tests: atlas `atlas` of texel pass `kind` rendered in UV space by the shading fragment
  // shader with this frame's lighting (updated first) at the display order, read back into
  // *out as linear RGBA (TexelRenderer::readAtlas). "" or the error.
  std::string texelAtlasRadiance(ShadingMode kind, int atlas, std::vector<float>* out, bool positions = false);

  // ---- glossy rendering (docs/web-client.md, "Glossy rendering") ----
  // Which terms pass `kind` draws: its diffuse vector pass, its glossy matrix pass, or both
  // (the default). Ignored for Lambert.
  void setGlossyMix(ShadingMode kind, GlossyMix mix);
  GlossyMix glossyMix(ShadingMode kind) const;
  // Whether the scene has (or is streaming) a glossy matrix pass of `kind`.
  bool hasGlossy(ShadingMode kind) const;
  // Bands of the glossy pass of `kind` on the GPU (0 when absent): the shells arrived so far.
  int glossyBands(ShadingMode kind) const { return renderer_.glossyOrder(kind); }
  // [clusters, basis matrices per cluster, channels] of the glossy pass of `kind`; zeros when absent.
  std::vector<int> glossyShape(ShadingMode kind) const {
    const auto s = renderer_.glossyShape(kind);
    return {s[0], s[1], s[2]};
  }
  // Decodes the glossy matrix pass of `kind` from its first `bands` shells (0: all that have
  // arrived) and re-uploads it. "" or the error.
  std::string streamGlossyPass(ShadingMode kind, int bands);
  // ---- bi-scale (docs/bi-scale.md, "The client") ----
  // Draw the scene bi-scale (the RTT per fragment over the glossy pass of the mode) when it has
  // an RTT; off by default, and kept as the wish across scenes.
  void setBiScale(bool on) { biScale_ = on; }
  bool biScale() const { return biScale_; }
  // Whether the scene has an RTT on the GPU; its bands (0: none).
  int biScaleOrder() const { return renderer_.biScaleOrder(); }
  // The RTT's view dependence (the paper's Figure 6 switch): off reads its centre view.
  void setViewDependence(bool on) { viewDependent_ = on; }
  bool viewDependence() const { return viewDependent_; }
  // Whether the last frame was drawn bi-scale.
  bool drewBiScale() const { return renderer_.drewBiScale(); }
  // Tests: the last bi-scale frame's rotated transferred radiance read back from the GPU, and
  // the same computed on the CPU (prt::ShRotation of the CPCA matrices' T under the frame's
  // lighting, biScaleRotateCpu's layout), flat; both empty when there is none.
  std::vector<float> biScaleRotated() const;
  std::vector<float> biScaleRotatedReference();
  // Schlick's Fresnel in the glossy term (on by default; off: k_s = f0, for comparisons).
  void setFresnel(bool on) { fresnel_ = on; }
  // GlRenderer::lastGlossyStep: "fused", "view" or "".
  std::string lastGlossyStep() const { return renderer_.lastGlossyStep(); }
  // Glossy radiance of every vertex in the last frame, flat RGB before exposure (GPU read-back).
  std::vector<float> vertexGlossy() const;
  // The CPU reference of the last frame's glossy term for pass `kind`: prt::glossyExitRadiance
  // on the matrices prt::cpcaMatrixReconstruct expands, with the last frame's lighting (read back from the GPU) and eye,
  // at the bands drawn; flat RGB per vertex, empty when the pass is absent.
  std::vector<float> glossyReference(ShadingMode kind);
  // Tests: replaces the glossy pass of `kind` by a synthetic CPCA matrix pass (glossy_synthetic.h:
  // `bands`, `channels`, `clusters`, `vectors`, `seed`) with material (f0, exponent) on every
  // vertex whose albedo's green channel is >= `minGreen`; the others get f0 = 0 and all-zero
  // matrices (no glossy term), as a bake stores non-glossy vertices. "" or the error.
  std::string useSyntheticGlossy(ShadingMode kind, int bands, int channels, int clusters, int vectors, int seed,
                                 float f0, float exponent, float minGreen);

  // Environment lighting: radiance SH, flat [r,g,b] per coefficient, order 1..16 (the first
  // kMaxClientOrder bands are kept). Returns "" or the error.
  std::string setEnvironment(const std::vector<float>& flatRgb, int order);
  // Constant radiance `intensity` from every direction (the white furnace).
  void setWhiteFurnace(float intensity);
  void setEnvRotation(float yawRadians, float pitchRadians);
  void setLightColor(float r, float g, float b);  // multiplies the lighting
  void setMode(ShadingMode mode);  // one whose pass is still streaming takes effect when it arrives
  void setDisplayOrder(int order);                 // clamped to [1, baked order]
  void setExposure(float ev);                      // exposure value, 2^ev
  // What is drawn behind the scene (gl_renderer.h BackgroundMode; docs/web-client.md,
  // "Background"). Blurred and image need the environment on; colour is drawn either way.
  void setBackgroundMode(BackgroundMode mode) { backgroundMode_ = mode; }
  void setBackgroundColour(float r, float g, float b) { backgroundColour_ = {r, g, b}; }  // sRGB, 0..1
  // The current environment's equirect map for the image background (GlRenderer::
  // setBackgroundImage): "" or why it was refused. Empty `texels` removes it; choosing
  // another environment (setEnvironment, setWhiteFurnace) removes it too, so a stale map
  // never shows behind new lighting.
  std::string setBackgroundImage(int width, int height, std::span<const std::uint32_t> texels);
  bool hasBackgroundImage() const { return renderer_.hasBackgroundImage(); }

  // ---- the camera (orbit_camera.h) ----
  void orbit(float dxRadians, float dyRadians) { camera_.orbit(dxRadians, dyRadians); }
  void pan(float dx, float dy) { camera_.pan(dx, dy); }  // in units of half the distance
  void zoom(float factor) { camera_.zoom(factor); }      // > 1 moves away
  // Frames the scene's bounding sphere (the centre and half diagonal of its bounds).
  void frameScene();
  // [targetX, targetY, targetZ, yaw, pitch, distance] (OrbitCamera::Pose), for permalinks.
  std::vector<float> cameraPose() const;
  // Sets what cameraPose() gives (pitch and distance clamped); false, nothing changed, when
  // `pose` is not six finite numbers.
  bool setCameraPose(const std::vector<float>& pose);
  // That sphere, in world units (radius 1 about the origin before a scene is loaded).
  float sceneRadius() const { return camera_.sceneRadius(); }
  Vec3 sceneCenter() const { return toVec3(camera_.sceneCenter()); }
  // The last frame's view-projection matrix, 16 floats column-major (all zero before the
  // first frame).
  std::vector<float> viewProjection() const;

  // Updates the lighting (rotation, colour, truncation) and draws one frame.
  void render(int width, int height);

  // Where world point (x, y, z) landed in the last frame: [ndcX, ndcY, depth], NDC in
  // [-1, 1] with +y up. Lets tests find scene features on screen without guessing.
  std::vector<float> project(float x, float y, float z) const;

  // The lighting of the last frame at the display order, flat [r,g,b] per coefficient:
  // the light cube's projection plus the environment when enabled. Reads the GPU-built
  // lighting block back (synchronous; tests and tools only).
  std::vector<float> lightSH();

  // ---- dynamic lights (docs/web-client.md, "Light cube"; API: emitters.h) ----
  // 16 floats per light; "" or an error naming the light and field (nothing changes).
  std::string setLights(const std::vector<float>& flat);
  // Local-unit mesh for shape 3; returns its id, or -1 on invalid input.
  int addLightMesh(std::vector<float> positions, std::vector<std::uint32_t> indices);
  // Whether the environment is added to the lighting (and drawn as the background).
  void setEnvironmentEnabled(bool on) { environmentEnabled_ = on; }
  std::string setProjection(int mode);  // 0 GPU, 1 CPU, 2 analytic; "" or why GPU is unavailable
  int projectionMode() const { return lights_.projectionMode(); }
  bool gpuProjectionSupported() const { return lights_.gpuProjectionSupported(); }
  std::string setCubeSize(int size);  // faces of size x size texels, 8..512
  int cubeSize() const { return lights_.cubeSize(); }
  void simulateNoFloatTargets(bool on) { lights_.simulateNoFloatTargets(on); }
  // The point the light cube is rendered from: the asset's lighting centre for the local
  // models, the scene bounds' centre for distant lighting. World units.
  Vec3 lightCenter() const;
  int lightingModel() const { return static_cast<int>(asset_.lighting.model); }
  float lightingRadius() const { return asset_.lighting.radius; }
  // The emitters' SH alone (light cube plus, on the analytic path, the analytic lights), flat
  // [r,g,b] per coefficient at the baked order (at most kMaxClientOrder); projects first if
  // lights, size, path or order changed since.
  std::vector<float> cubeSH();
  // Re-projects the lights now, without drawing (benchmarks): the whole light cube on the
  // GPU/CPU paths; on the analytic path light `onlyLight` (all when < 0), as a drag moving it does.
  void projectLightsNow(int onlyLight);
  void finishGpu();  // waits until the GPU has done all queued work (benchmarks)
  // Benchmarks: the per-vertex PRT pass of the current mode alone, as render() runs it
  // (lighting updated first), without drawing; false when the mode has no pass.
  bool shadeVertices();
  // Benchmarks: the glossy work of the current mode alone (lighting updated first), as
  // `work` (GlossyWork: 0 as a frame needs it, 1 the per-cluster table alone, 2 table and
  // fused step, 3 the per-vertex view step alone, 4 table, transferred radiance and view step).
  bool shadeGlossyVertices(int work);
  // Waits for the glossy passes queued so far (a 1-value read-back of what they write).
  void finishGlossy(int work) const {
    if (!ok()) return;
    makeCurrent();
    renderer_.finishGlossy(mode_, static_cast<GlossyWork>(work));
  }
  // Benchmarks: the next frame treats the lighting as changed (as when a light moves), so
  // the glossy term's view-independent work runs again.
  void touchLighting() { lights_.touchBlock(); }
  void finishShading() const;  // waits for the PRT passes queued so far (a 1-vertex read-back)
  std::size_t weightTableBytes() const { return lights_.weightTableBytes(); }
  const std::string& projectionError() const { return lights_.projectionError(); }
  // World-space ray through NDC point (x, y) of the last frame: {origin (the eye), unit dir}.
  std::vector<float> rayFromScreen(float ndcX, float ndcY) const;

  std::size_t vertexCount() const { return asset_.positions.size(); }
  std::size_t triangleCount() const { return asset_.indices.size() / 3; }
  int bakedOrder() const { return asset_.shOrder; }
  int displayOrder() const { return displayOrder_; }
  ShadingMode mode() const { return mode_; }
  bool hasPass(ShadingMode mode) const { return ok() && renderer_.hasPass(mode); }
  // A pass of `mode` in the drawn domain is on the GPU: a vector or glossy vertex pass, or the
  // texel pass (Lambert: the geometry).
  bool hasAnyPass(ShadingMode mode) const;

 private:
  bool ok() const { return error_.empty(); }
  void updateLighting();
  void prepareLighting();  // updateLighting, the light cube and the lighting block, as a frame needs them
  void makeCurrent() const;
  void syncLightView();  // light-cube centre, near plane and order from the scene
  void adoptGeometry(BakedAsset decoded);  // bounds, order, mode, framing of a new scene
  // Uploads a glossy pass and keeps its CPU copy for glossyReference. "" or the error.
  std::string uploadGlossy(TransferKind kind, CpcaMatrixTransfer cpca);
  // Whether pass kind `mode` of domain `d` is on the GPU or still streaming.
  bool offers(ShadingMode mode, TransferDomain d) const;
  // source_ from wantedSource_ and what the scene has; then, if the displayed pass kind is not
  // offered in that domain, the richest that is (interreflected, shadowed, unshadowed).
  void resolveSource();
  // Remakes the texel glossy term's product matrix P(L) when the scene has a visibility pass and
  // the lighting or the bands changed since. "" or the error.
  std::string updateTexelProduct();
  TexelShading texelShading() const;  // the frame's terms, order, eye for the texel draw

  std::string error_;
  GlContext context_;
  GlRenderer renderer_;
  DynamicLighting lights_;
  bool environmentEnabled_ = true;
  bool cpcaDirect_ = true;
  bool fresnel_ = true;
  bool biScale_ = false;
  bool viewDependent_ = true;
  std::array<GlossyMix, 3> glossyMix_{GlossyMix::kBoth, GlossyMix::kBoth, GlossyMix::kBoth};
  std::array<CpcaMatrixTransfer, 3> glossyCpu_{};  // the uploaded glossy passes, for glossyReference
  glm::vec3 lastEye_{0.0f};
  std::optional<std::uint64_t> productVersion_;  // lighting version and bands of the uploaded P(L)
  std::string productError_;
  std::vector<std::uint8_t> pending_;
  AssetStream stream_;
  BakedAsset asset_;
  Vec3 boundsMin_{}, boundsMax_{};

  std::vector<Rgb> environment_;  // unrotated
  int environmentOrder_ = 1;
  float yaw_ = 0, pitch_ = 0;
  Rgb color_{1, 1, 1};
  std::vector<Rgb> lighting_;  // rotated and coloured, at environmentOrder_
  float packed_[kPackedLightingFloats] = {};

  ShadingMode mode_ = ShadingMode::kInterreflected;
  TransferDomain wantedSource_ = TransferDomain::kVertex, source_ = TransferDomain::kVertex;
  std::optional<ShadingMode> pendingMode_;  // a mode asked for whose pass is still streaming
  int displayOrder_ = kMaxClientOrder;
  float exposure_ = 1.0f;
  BackgroundMode backgroundMode_ = BackgroundMode::kImage;
  glm::vec3 backgroundColour_{0.1f};
  glm::mat3 environmentRotation_{1.0f};  // R of the last updateLighting, for the image background

  OrbitCamera camera_;
};

}  // namespace prt::web
