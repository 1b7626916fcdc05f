// The analytic half of the dynamic lighting (docs/analytic-lights.md): sphere, disc and rect
// emitters projected onto SH in closed form from the lighting centre c, one cached unit-
// radiance vector per light, so moving one light re-projects that light only and then sums
// the cache. GL-free (tested under Node through core_bindings).
#pragma once

#include <span>
#include <vector>

#include "emitters.h"
#include "prt/sh_polygon.h"
#include "prt/status.h"

namespace prt::web {

class AnalyticLights {
 public:
  // Whether this path handles the shape (sphere, disc, rect; meshes keep the light cube).
  static bool handles(EmitterShape shape) { return shape != EmitterShape::kMesh; }

  // Projection order (1..8) and centre; a change marks every light dirty. Errors on a bad order.
  Status setView(Vec3 center, int order);
  // Replaces the lights (`flat`: 16 floats per light, already parsed into `emitters`). A light
  // whose 16 floats equal the same index's before keeps its cached SH.
  void setEmitters(std::span<const Emitter> emitters, std::span<const float> flat);
  // Marks light `index` dirty (all when index < 0): benchmarks re-project on demand.
  void invalidate(int index);
  bool dirty() const { return anyDirty_; }
  // Re-projects the dirty lights and writes the sum of all analytic lights, scaled by their
  // radiance, into `packed` (packLighting layout, kPackedLightingFloats floats; coefficients
  // at or above the order zero).
  void update(float* packed);
  // Counts analytic lights (the shapes `handles`).
  int count() const { return analyticCount_; }

  // The SH of one emitter of radiance 1 seen from `center` at `order` into out[0 .. order^2)
  // (added): sphere as a cap, disc as a kDefaultDiscEdges-gon, rect as its quad; zero when
  // `center` is inside the sphere or not in front of the disc or rect (one-sided, as the cube
  // renders them). Errors only for a mesh emitter.
  static Status projectEmitter(const PolygonShProjector& projector, const Emitter& e, Vec3 center, double* out);

 private:
  struct Light {
    float key[kFloatsPerEmitter] = {};
    Emitter emitter;
    bool analytic = false, dirty = true;
    std::vector<double> sh;  // order^2, radiance 1
  };
  PolygonShProjector projector_;
  std::vector<Light> lights_;
  Vec3 center_{};
  int order_ = 0, analyticCount_ = 0;
  bool anyDirty_ = true;
};

}  // namespace prt::web
