#include "prt/patch_placement.h"

#include <cmath>

namespace prt {
namespace {

// x - floor(x) rounds up to 1 for tiny negative x; the RTT's index must stay below 1.
float wrapUnit(float x) {
  const float f = x - std::floor(x);
  return f >= 0.0f && f < 1.0f ? f : 0.0f;
}

}  // namespace

void patchCoordinates(const PatchPlacement& placement, Vec3 p, float* u, float* v) {
  const Vec3 d = p - placement.origin;
  *u = wrapUnit(dot(d, placement.axisU));
  *v = wrapUnit(dot(d, placement.axisV));
}

Vec3 patchTangent(Vec3 normal) {
  const float len = length(normal);
  if (!(len > 0.0f) || !std::isfinite(len)) return {1, 0, 0};
  // Divided, not multiplied by 1 / len: a subnormal length's reciprocal overflows.
  const Vec3 n{normal.x / len, normal.y / len, normal.z / len};
  Vec3 t = Vec3{1, 0, 0} - n * n.x;
  float tl = length(t);
  if (tl < kPatchTangentFallback) {
    // |n.x| > 0.95 here, so |n.z| < 0.31 and +z projects to at least 0.95.
    t = Vec3{0, 0, 1} - n * n.z;
    tl = length(t);
  }
  return t * (1.0f / tl);
}

}  // namespace prt
