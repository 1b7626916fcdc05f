// Dynamic area lights and the lighting they produce (docs/web-client.md, "Light cube" and
// "Analytic lights"): the emitters; on the analytic path (the default) spheres, discs and
// rects projected in closed form (AnalyticLights) and only mesh emitters in the light cube;
// on the GPU and CPU paths every emitter in the cube, rendered from the lighting centre
// whenever its emitters, the cube size, the path or the order change and projected on the
// GPU (CubeShReduction) or the CPU (readPixels + the shared projectCubeMap); and the
// lighting block the shading programs read (cube SH + analytic SH + environment). The
// emitters are also drawn in the main view.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "analytic_lights.h"
#include "cube_sh_reduction.h"
#include "emitter_renderer.h"
#include "emitters.h"
#include "light_cube.h"
#include "lighting_block.h"
#include "prt/status.h"

namespace prt::web {

enum class ProjectionPath : int { kGpu = 0, kCpu = 1, kAnalytic = 2 };

class DynamicLighting {
 public:
  inline static constexpr int kDefaultCubeSize = 64;
  inline static constexpr int kMinCubeSize = 8;
  inline static constexpr int kMaxCubeSize = 512;

  // Builds the GL objects; `floatTargets`: EXT_color_buffer_float is enabled. Context current.
  Status init(bool floatTargets);

  std::string setLights(std::span<const float> flat);  // "" or the error (nothing changes)
  int addLightMesh(std::vector<float> positions, std::vector<std::uint32_t> indices);  // id or -1
  std::string setProjection(int mode);  // 0 GPU, 1 CPU, 2 analytic (meshes on the GPU, else the CPU)
  int projectionMode() const { return static_cast<int>(path_); }
  bool gpuProjectionSupported() const { return floatTargets_ && !simulateNoFloat_; }
  std::string setCubeSize(int size);
  int cubeSize() const { return cubeSize_; }
  // Test aid: behave as if EXT_color_buffer_float were missing (RGBE8 cube, CPU path).
  void simulateNoFloatTargets(bool on);

  // Where the cube is rendered from and the SH order it is projected to (1..kMaxClientOrder); the near
  // plane is `sceneRadius` * 1e-4. Changes mark the cube dirty.
  void setView(Vec3 center, float sceneRadius, int order);
  Vec3 center() const { return center_; }

  // Makes the lighting block current for a frame: re-projects the cube if dirty, then
  // rebuilds the block if the cube, `environment` (packLighting layout, kPackedLightingFloats, zero
  // when off) or the display order changed. Leaves the block bound.
  void update(const float* environment, int displayOrder);
  // Counts the block's rebuilds: equal across two updates only if the block's values did not change.
  unsigned lightingVersion() const { return blockVersion_; }
  // Benchmarks: the next update rebuilds the block as if the lighting had changed.
  void touchBlock() { combinedOrder_ = 0; }
  // Benchmarks: re-projects the lights now, whatever the dirty flags say. GPU/CPU paths: the
  // whole cube. Analytic path: light `onlyLight` (every light when < 0), the cached sum, the
  // cube only if it holds mesh emitters, and the block rebuilt (no finish, no readback).
  void projectNow(int onlyLight = -1);
  // Waits for all queued GL work: glFinish, then a 1-texel readPixels of the cube-SH
  // texture (Chrome's WebGL finish does not block; a readback does).
  void finishGpu();
  // Draws the emitters into the bound framebuffer (depth-tested, tone-mapped).
  void drawEmitters(const glm::mat4& viewProjection, Vec3 eye, float exposure);

  const std::vector<Emitter>& emitters() const { return emitters_; }
  const std::vector<BoundingSphere>& emitterBounds() const { return bounds_; }
  // The lighting block of the last update, flat [r,g,b] per coefficient, displayOrder^2 rows.
  std::vector<float> lightSH() const;
  // The emitters' SH alone (no environment): the last cube projection plus, on the analytic
  // path, the analytic lights; flat [r,g,b] per coefficient at the projection order.
  std::vector<float> cubeSH();
  std::size_t weightTableBytes() const { return reduction_.weightBytes(); }
  // Why the last projection did not run as asked ("" when it did): e.g. a weight table over
  // budget on the GPU path (then the CPU path ran), or a failed readback (no light then).
  const std::string& projectionError() const { return projectionError_; }

 private:
  void project();
  void selectCubeEmitters();
  bool analyticPath() const { return path_ == ProjectionPath::kAnalytic; }
  // The cube's SH when it runs on the GPU (mesh emitters on the analytic path), else the CPU.
  bool cubeOnGpu() const { return (path_ == ProjectionPath::kGpu || analyticPath()) && gpuProjectionSupported(); }
  // The block's non-cube input: environment + analytic SH cut to displayOrder. Rebuilds the
  // block (bumping blockVersion_) only if it or the cube changed.
  void combine(const float* environment, int displayOrder, bool force);
  Status projectOnGpu();
  Status projectOnCpu();

  EmitterRenderer renderer_;
  LightCube cube_;
  CubeShReduction reduction_;
  LightingBlock block_;
  std::vector<LightMesh> meshes_;
  std::vector<Emitter> emitters_;
  std::vector<BoundingSphere> bounds_;
  std::vector<float> flat_;                // emitters_ as given, 16 floats each
  std::vector<Emitter> cubeEmitters_;      // what the cube renders: all, or the meshes (analytic)
  std::vector<BoundingSphere> cubeBounds_;
  std::vector<float> cubeFlat_;            // their 16 floats, to tell whether the cube changed
  AnalyticLights analytic_;
  float analyticSh_[kPackedLightingFloats] = {};   // packLighting layout, zero off the analytic path
  float environment_[kPackedLightingFloats] = {};  // the last update's environment
  bool floatTargets_ = false, simulateNoFloat_ = false;
  ProjectionPath path_ = ProjectionPath::kAnalytic;
  int cubeSize_ = kDefaultCubeSize, order_ = 5;
  Vec3 center_{};
  float nearZ_ = 1e-4f;
  bool dirty_ = true, cubeEmpty_ = true;
  unsigned cubeVersion_ = 1, combinedVersion_ = 0, blockVersion_ = 0;
  float combinedEnvironment_[kPackedLightingFloats] = {};
  int combinedOrder_ = 0;
  std::vector<float> cpuCubeSh_;  // packLighting layout, valid on the CPU path and when empty
  bool lastOnGpu_ = false;        // where cpuCubeSh_ or the cube-SH texture holds the last projection
  std::string projectionError_;
};

}  // namespace prt::web
