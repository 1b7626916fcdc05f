// Dynamic area lights and the lighting they produce (docs/web-client.md, "Light cube"): the
// emitters, the light cube rendered from the lighting centre whenever the lights, cube
// size, projection path or order change, its SH projection on the GPU (CubeShReduction) or
// on the CPU (readPixels + the shared projectCubeMap), and the lighting block the shading
// programs read (cube SH + environment). The emitters are also drawn in the main view.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "cube_sh_reduction.h"
#include "emitter_renderer.h"
#include "emitters.h"
#include "light_cube.h"
#include "lighting_block.h"
#include "prt/status.h"

namespace prt::web {

enum class ProjectionPath : int { kGpu = 0, kCpu = 1 };

class DynamicLighting {
 public:
  inline static constexpr int kDefaultCubeSize = 64;
  inline static constexpr int kMinCubeSize = 8;
  inline static constexpr int kMaxCubeSize = 512;

  // Builds the GL objects; `floatTargets`: EXT_color_buffer_float is enabled. Context current.
  Status init(bool floatTargets);

  std::string setLights(std::span<const float> flat);  // "" or the error (nothing changes)
  int addLightMesh(std::vector<float> positions, std::vector<std::uint32_t> indices);  // id or -1
  std::string setProjection(int mode);  // 0 GPU, 1 CPU
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
  // Re-renders and re-projects the cube now, whatever the dirty flag says (benchmarks).
  void projectNow();
  // Waits for all queued GL work: glFinish, then a 1-texel readPixels of the cube-SH
  // texture (Chrome's WebGL finish does not block; a readback does).
  void finishGpu();
  // Draws the emitters into the bound framebuffer (depth-tested, tone-mapped).
  void drawEmitters(const glm::mat4& viewProjection, Vec3 eye, float exposure);

  const std::vector<Emitter>& emitters() const { return emitters_; }
  const std::vector<BoundingSphere>& emitterBounds() const { return bounds_; }
  // The lighting block of the last update, flat [r,g,b] per coefficient, displayOrder^2 rows.
  std::vector<float> lightSH() const;
  // The last cube projection alone, flat [r,g,b] per coefficient at the projection order.
  std::vector<float> cubeSH();
  std::size_t weightTableBytes() const { return reduction_.weightBytes(); }
  // Why the last projection did not run as asked ("" when it did): e.g. a weight table over
  // budget on the GPU path (then the CPU path ran), or a failed readback (no light then).
  const std::string& projectionError() const { return projectionError_; }

 private:
  void project();
  Status projectOnGpu();
  Status projectOnCpu();

  EmitterRenderer renderer_;
  LightCube cube_;
  CubeShReduction reduction_;
  LightingBlock block_;
  std::vector<LightMesh> meshes_;
  std::vector<Emitter> emitters_;
  std::vector<BoundingSphere> bounds_;
  bool floatTargets_ = false, simulateNoFloat_ = false;
  ProjectionPath path_ = ProjectionPath::kGpu;
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
