// Brute-force direct lighting from an emitter on the local lighting sphere: the independent
// reference the spatially-varying transfer is tested and benchmarked against
// (docs/spatially-varying.md). It integrates over the emitter's area with Embree visibility,
// sharing nothing with the transfer bake but the scene and the ray offsets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "prt/status.h"
#include "prt/vec3.h"
#include "baker/scene/scene.h"

namespace prt::bake {

// A spherical cap of the lighting sphere S (center, radius): the points of S within
// halfAngle of c + r axis, each a Lambertian emitter of radiance `radiance` facing the
// inside of S. Seen from c it is a circular light of angular radius halfAngle about axis,
// whose SH projection is Lisle & Huang's closed form (capLightingSh).
struct CapEmitter {
  Vec3 center;              // c, world units
  float radius = 1.0f;      // r > 0
  Vec3 axis{0, 1, 0};       // unit-or-not, non-zero
  float halfAngle = 0.25f;  // radians, (0, pi]; pi is the whole sphere
  float radiance = 1.0f;    // Le
  // Optional: radiance varying over the cap, Le * radianceAt(w') at the point c + r w'
  // (w' unit). Lets a test use lighting that SH represents exactly, free of truncation.
  std::function<float(Vec3)> radianceAt;
};

struct DirectReferenceOptions {
  std::size_t samples = 16384;  // points on the cap per vertex, 1..1<<24
  std::uint64_t seed = 0;       // 0: the plain Hammersley set; else a seeded random shift of it
  unsigned threads = 0;         // 0: all hardware threads; results do not depend on it
};

// Irradiance per vertex, E(x) = integral over the cap of Le(y) V(x, y) max(0, n.w) cos(theta_y) / |x - y|^2 dA(y),
// with w = (y - x)/|y - x| and cos(theta_y) = max(0, w.(y - c)/r), the cosine at the
// inward-facing emitter. Points y are a 2D Hammersley set mapped uniformly by area onto the
// cap (each weighs area / samples); visibility rays start at x + eps n with the bake's eps
// and stop eps short of y. Exit radiance is albedo / pi * E. Deterministic.
Status directIrradianceFromCap(const Scene& scene, const CapEmitter& cap, const DirectReferenceOptions& options,
                               std::vector<double>* irradiance);

// The SH lighting vector (order^2 coefficients) that a cube map rendered at the cap's
// centre records for it: a circular light (zonalCircularLight placed on the axis).
// Uniform caps only (radianceAt empty).
Status capLightingSh(const CapEmitter& cap, int order, std::vector<float>* coeffs);

}  // namespace prt::bake
