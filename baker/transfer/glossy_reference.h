// Brute-force glossy reference (docs/glossy.md): the glossy exit radiance of a vertex toward
// an eye, integrated by Monte Carlo straight from a radiance function, with Embree
// visibility and no spherical harmonics. The glossy bake and its SH evaluation are tested
// and benchmarked against it, so that their error splits into SH truncation (compare with
// the same function truncated to SH) and bake/codec error.
//
//   L_o = k_s * integral L(w) V(x, w) [n.w > 0] f(w) dw,  f(w) = (s+1)/(2pi) max(0, R.w)^s
// sampled by the lobe itself, pdf(w) = (s+1)/(2pi) (R.w)^s on R.w > 0, so f/pdf = 1 and the
// estimate is k_s times the mean of L V [n.w > 0] over the samples. Direct light only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "prt/asset.h"
#include "prt/status.h"
#include "prt/vec3.h"
#include "baker/scene/scene.h"

namespace prt::bake {

struct GlossyReferenceOptions {
  std::size_t samples = 16384;  // lobe samples per vertex, 1..1<<24
  std::uint64_t seed = 0;       // 0: the plain Hammersley set; else a seeded random shift of it
  bool includeFresnel = true;   // false: k_s = f0 (the lobe alone), as GlossyView::includeFresnel
  unsigned threads = 0;         // 0: all hardware threads; results do not depend on it
};

// Radiance arriving from direction `dir` (unit): for distant lighting the direction of
// travel reversed (toward the light); for local lighting the direction from the sphere's
// centre c to the point of S the ray reaches (what a cube map rendered at c records).
using RadianceFunction = std::function<Rgb(Vec3 dir)>;

// Glossy exit radiance (RGB) of scene vertices `vertices` toward `eye`, materials from
// scene.specular (required, one per position). lighting: distant, or kLocalSphere (the
// physical incident radiance L(w') of a sphere of emitters; the paper form, which is not a
// radiance, is rejected). Visibility rays start at x + eps n with the bake's eps and stop
// where they leave S for local lighting; rays that never reach S carry nothing. A vertex
// at the eye gets 0. Deterministic. Errors name the bad argument.
Status glossyReferenceRadiance(const Scene& scene, std::span<const std::uint32_t> vertices, Vec3 eye,
                               const LightingInfo& lighting, const RadianceFunction& radiance,
                               const GlossyReferenceOptions& options, std::vector<Rgb>* out);

}  // namespace prt::bake
