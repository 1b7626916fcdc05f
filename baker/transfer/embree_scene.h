// RAII ownership of an Embree device and a committed triangle scene built from a bake::Scene.
#pragma once

#include <embree3/rtcore.h>

#include "prt/status.h"
#include "baker/scene/scene.h"

namespace prt::bake {

class EmbreeScene {
 public:
  EmbreeScene() = default;
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  ~EmbreeScene();

  // Builds the BVH over `scene` (positions and indices are copied into Embree buffers;
  // `scene` may be freed afterwards). Errors name Embree's error code. `robust`: Embree's
  // watertight traversal (RTC_SCENE_FLAG_ROBUST), for rays aimed exactly at vertices and
  // edges (the RTT bake's view rays through grid points), at some speed.
  static Status build(const Scene& scene, EmbreeScene* out, bool robust = false);

  RTCScene handle() const { return scene_; }
  // Length of the bounding-box diagonal (metres): the scale ray offsets are relative to.
  float diagonal() const { return diagonal_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  float diagonal_ = 0.0f;
};

}  // namespace prt::bake
