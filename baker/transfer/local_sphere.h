// Geometry of spatially-varying ("local sphere") lighting, docs/spatially-varying.md.
//
// The lighting is radiance L(w') on a sphere S of radius r about c, indexed by the direction
// w' from c (what a cube map rendered at c records). A ray from x along w reaches S at
// x + t* w, where S's point has direction w'(x, w) = (x - c + t* w) / r from c. The local
// transfer integrates the same sample directions w as the distant one, with visibility
// limited to t* and the SH basis evaluated at w' instead of w.
#pragma once

#include "prt/asset.h"
#include "prt/vec3.h"
#include "baker/scene/scene.h"

namespace prt::bake {

// Smallest cos(theta') the paper variant divides by: its weight 1/cos(theta') is clamped to
// 1/kPaperMinCosine = 20. Inside S, cos(theta') >= sqrt(1 - (|x-c|/r)^2), so the clamp acts
// only within 0.13% of r from S.
inline constexpr float kPaperMinCosine = 0.05f;

// A vertex's position relative to S, computed once per vertex.
struct SpherePoint {
  Vec3 p;              // x - c
  float delta = 0.0f;  // r^2 - |x - c|^2, >= 0 inside or on S
  float radius = 0.0f;
  float invRadius = 0.0f;
  bool outside = false;  // |x - c| > r beyond float rounding: some rays never reach S
};

// Where x lies with respect to the sphere (center, radius > 0). Points within a relative
// 1e-6 of the surface count as on it (delta = 0), so vertices that the default sphere puts
// exactly on S (bounding-box corners) are not reported outside because of rounding.
SpherePoint locateOnSphere(Vec3 x, Vec3 center, float radius);

// Distance t* > 0 along unit `w` from x to where the ray leaves S, or a negative value when
// the ray never leaves S going forward (x outside S and the ray misses or points away).
// Cancellation-free in both root orders.
float exitDistance(const SpherePoint& s, Vec3 w);

// The per-ray remapping of one sample direction: what the lighting is looked up with and
// how much the ray weighs relative to its solid-angle weight.
struct RemappedRay {
  Vec3 lightDir;       // w' = (x - c + t* w) / r, unit to float rounding; w when !reachesLight
  float tFar = 0.0f;   // t*: occluders beyond S do not block; +inf when !reachesLight
  float weight = 0.0f; // 1 for the area form; 1 / max(w.w', kPaperMinCosine) for the paper's; 0 when !reachesLight
  bool reachesLight = false;
};

// Remaps direction `w` (unit) for the point `s` under lighting `model` (a local model).
RemappedRay remapRay(const SpherePoint& s, Vec3 w, LightingModel model);

// The default sphere of a local model for `scene`: centred on its bounding box, radius half
// the box's diagonal (every vertex inside, the box's corners on S), or 1 for a scene without
// extent. `model` must be a local one.
LightingInfo defaultLightingSphere(const Scene& scene, LightingModel model);

}  // namespace prt::bake
