// Ray casting against a periodic height-field patch (baker/rtt/height_patch.h): the patch's
// mesh over 3 x 3 periods in Embree, and rays that wrap around the centre period, so a ray may
// travel any number of periods (near-horizontal light directions cross dozens) over one
// period's geometry. The neighbouring copies keep the mesh watertight across the seams.
#pragma once

#include <cstdint>
#include <vector>

#include "baker/rtt/height_patch.h"
#include "baker/transfer/embree_scene.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::bake {

// A ray's first hit: the triangle of the 3 x 3 mesh and Embree's barycentrics (the point is
// (1 - u - v) p0 + u p1 + v p2).
struct PeriodicHit {
  bool hit = false;
  std::uint32_t triangle = 0;
  float u = 0.0f, v = 0.0f;
};

class PeriodicTracer {
 public:
  // Builds the BVH of `patch`'s mesh: grid points joined into two triangles a cell.
  static Status build(const HeightPatch& patch, PeriodicTracer* out);

  // The first patch point along origin + t dir, t >= 0 (dir unit; origin's x and y are taken
  // modulo 1). No hit when the ray leaves the patch's height range upward (or, for a
  // near-horizontal ray, after kMaxPeriods periods without a hit).
  PeriodicHit firstHit(Vec3 origin, Vec3 dir) const;
  // The first patch point the viewer along `toViewer` (unit, z > 0) sees through `point`:
  // the ray through `point` along -toViewer, from above the patch.
  PeriodicHit viewHit(Vec3 point, Vec3 toViewer) const;
  // `stride` floats a grid point of `perPoint` interpolated at `hit` into out[0 .. stride).
  void interpolate(const PeriodicHit& hit, const std::vector<float>& perPoint, std::size_t stride, float* out) const;
  // The grid points (j * size + i) at the hit triangle's corners, in Embree's vertex order.
  std::vector<std::size_t> triangleGridPoints(const PeriodicHit& hit) const;

  float minHeight() const { return minHeight_; }
  float maxHeight() const { return maxHeight_; }

  static constexpr int kMaxPeriods = 4096;

 private:
  EmbreeScene embree_;
  std::vector<std::uint32_t> gridPointOf_;  // mesh vertex -> the grid point it copies
  std::vector<std::uint32_t> indices_;      // the mesh's triangles
  float minHeight_ = 0.0f, maxHeight_ = 0.0f;
};

}  // namespace prt::bake
