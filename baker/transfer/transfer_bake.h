// Diffuse PRT transfer by Monte Carlo ray casting with Embree (Sloan et al. 2002; Fujita &
// Kanai 2004 §2; the Gentle Introduction §5-6).
//
// For vertex x with normal n and albedo rho, over one shared set of sample directions w_k
// with weight 4pi/N each (basis values y_i(w_k) computed once for all vertices):
//   unshadowed   U_i(x) = (1/pi) sum_k w max(0, n.w_k) y_i(w_k)                (scalar)
//   shadowed     S_i(x) = (1/pi) sum_k w V(x, w_k) max(0, n.w_k) y_i(w_k)      (scalar)
//   bounce 0     B0_ci(x) = rho_c(x) S_i(x)                                     (RGB)
//   bounce b     Bb_ci(x) = rho_c(x)/pi sum_{k hits front face} w max(0, n.w_k) Bb-1_ci(h_k)
//   interreflected T_ci(x) = sum_b Bb_ci(x)
// where h_k is the hit point of the ray from x along w_k and Bb-1(h_k) is interpolated
// from the hit triangle's vertices with the hit's barycentrics (Fujita & Kanai's gather
// from interpolated hit points). Exit radiance under lighting L is rho_c * sum_i U_i L_ci
// (or S_i), and sum_i T_ci L_ci for interreflection, whose albedo is folded in.
//
// Spatially-varying lighting (BakeOptions::lighting local; Fujita & Kanai §3.1,
// docs/spatially-varying.md): L is radiance on a sphere S (c, r) indexed by direction from
// c. The direct pass shoots the same w_k, stops visibility at t*, where the ray leaves S,
// and projects onto y_i(w'_k) with w'_k = (x - c + t* w_k)/r instead of y_i(w_k), one basis
// evaluation per ray; the paper variant also divides by cos(theta') = w_k.w'_k. Bounces
// gather exactly as for distant lighting.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/status.h"
#include "baker/scene/scene.h"

namespace prt::bake {

enum class Sampling { kHammersley, kStratified };

struct BakeProgress {
  const char* pass;          // "direct", "bounce N" or "glossy bounce N"
  std::size_t done, total;   // vertices
  std::uint64_t rays;        // rays cast so far in this pass
};

struct BakeOptions {
  int order = 5;                  // 2..8
  std::size_t samples = 1024;     // directions over the sphere (about half face any normal)
  Sampling sampling = Sampling::kHammersley;
  std::uint64_t seed = 1;         // rotates the Hammersley set / seeds the stratified jitter
  bool interreflection = true;    // shadowed and unshadowed are always computed
  int maxBounces = 8;             // hard cap on interreflection bounces
  double bounceThreshold = 1e-3;  // stop once a bounce adds less than this fraction of bounce 0's energy
  unsigned threads = 0;           // 0: all hardware threads; results do not depend on it
  LightingInfo lighting;          // distant (default) or a local sphere (checkLightingInfo rules)
  // Glossy transfer matrices (docs/glossy.md): the shadowed matrix of every vertex and, when
  // glossyBounces > 0, the interreflected one gathering that many bounces from diffuse and
  // glossy senders (at most the diffuse bounces gathered; needs interreflection).
  bool glossy = false;
  int glossyBounces = 1;          // 0..maxBounces
  std::function<void(const BakeProgress&)> progress;  // called from worker threads, serialised
};

struct PassStats {
  std::string name;
  double seconds = 0.0;
  std::uint64_t rays = 0;  // rays cast (0 for gather-only bounce passes)
};

// Work of the glossy shadowed matrix's rank-k update (ssyrk, or sgemm for local lighting):
// flops counted as BLAS does (syrk: K n2 (n2+1), gemm: 2 K n2^2) and seconds summed over
// the worker threads (gathering the rows and packing the result included).
struct GlossyKernelStats {
  std::uint64_t flops = 0;
  double threadSeconds = 0.0;
};

struct BakeResult {
  int order = 0;
  std::vector<float> unshadowed;      // [vertex][coefficient]
  std::vector<float> shadowed;        // [vertex][coefficient]
  std::vector<float> interreflected;  // [vertex][channel][coefficient], empty if not requested
  int bounces = 0;                    // bounces actually gathered
  std::vector<double> bounceEnergy;   // per bounce: sum over vertices of area x DC term, all channels
  std::vector<PassStats> passes;
  // Glossy (options.glossy): transferred incident radiance matrices, no albedo.
  // glossyShadowed: [vertex][packed entry], packing matrixPackingFor(kShadowed, lighting model):
  //   (M_x)_ij = sum_k (4pi/N) V(x, w_k) [n.w_k > 0] y_i(w_k) y_j(w'_k)   (w' = w for distant)
  // glossyInterreflected: [vertex][channel][packed entry], full packing: the shadowed matrix
  //   plus glossyBounces bounces; empty when glossyBounces is 0.
  std::vector<float> glossyShadowed;
  std::vector<float> glossyInterreflected;
  int glossyBounces = 0;              // bounces actually gathered into glossyInterreflected
  GlossyKernelStats glossyRankUpdate; // the shadowed matrices' rank-k updates, for benchmarks
  // Local lighting: vertices outside the sphere S, whose rays that miss S carry no light.
  std::size_t verticesOutsideLight = 0;
};

// Bakes all passes for `scene` (normals unit length, albedo in [0, 1]; in a closed scene of albedo 1 the bounce
// series converges only as far as maxBounces allows). Deterministic for
// a given (scene, options) whatever options.threads. Memory: the outputs plus, with
// interreflection, 12 bytes per occluded ray (hit triangle, barycentrics, weight), 16 with
// glossy (the sample index). Glossy: the shadowed matrices (order^2 (order^2+1)/2 floats
// per vertex distant, order^4 local), glossyInterreflected (3 order^4 floats per vertex,
// written bounce by bounce) and, for glossyBounces >= 2 only, two bounces of RGB matrices at
// the glossy senders (f0 > 0) alone; bounce 1 reads the scalar shadowed matrices (copied
// dense, order^4 floats, at the glossy senders) and the diffuse bounce vectors. Glossy passes set the BLAS (OpenBLAS) single-threaded for the
// process: the baker's threads split the vertices.
Status bakeTransfer(const Scene& scene, const BakeOptions& options, BakeResult* out);

}  // namespace prt::bake
