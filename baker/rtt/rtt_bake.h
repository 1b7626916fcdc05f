// Baking a radiance transfer texture from a height-field patch (Sloan et al. 2003 §4.2;
// docs/bi-scale.md): the meso-scale surface's transfer with self-shadowing and
// interreflection, seen from every view sample through every spatial sample.
#pragma once

#include <functional>

#include "baker/rtt/height_patch.h"
#include "prt/rtt.h"
#include "prt/status.h"

namespace prt::bake {

struct RttSettings {
  int order = 5;         // SH bands of B
  int spatial = 64;      // S x S spatial samples
  int views = 8;         // V x V view samples; 1: the view-independent (diffuse) special case
  int supersample = 2;   // ss x ss view rays a spatial sample, box-filtered (the paper: 2 x 2)
  // Light directions over the patch's upper hemisphere, a product rule: Gauss-Legendre nodes
  // in cos(theta) times uniform azimuths (the paper's 8 polar x 16 azimuthal directions).
  int lightPolar = 8;
  int lightAzimuth = 16;
  int bounces = 1;       // meso-scale interreflection bounces (0: shadowing only)
  unsigned threads = 0;  // 0: every hardware thread
};

// Called with (stage "direct", "bounce" or "views", rows done, rows) as the bake advances:
// with 0 done from the calling thread as each stage starts, then from the first worker
// thread only (never two calls at once); may be empty.
using RttProgress = std::function<void(const char* stage, std::size_t done, std::size_t total)>;

// Bakes `patch` into *out. Lambertian meso-surface (albedo / pi), lighting at infinity in the
// patch frame (prt/rtt.h). Per grid point of the patch's mesh (its size^2 points, periodic),
// the transfer vector t(x) = (rho / pi) sum_k w_k max(0, n.s_k) V(x, s_k) y(s_k) over the light
// directions s_k, plus `bounces` gathers over the same directions from the interpolated
// transfer where a direction hits the patch; then B(u, w) = t(x(u, w)) with x(u, w) the first
// hit of the ray through (u, mid-depth) along -w, averaged over the supersamples. Rays wrap
// around the patch's period. kInvalidArgument for settings out of range.
Status bakeRtt(const HeightPatch& patch, const RttSettings& settings, const RttProgress& progress, Rtt* out);

}  // namespace prt::bake
