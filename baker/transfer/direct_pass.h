// The direct pass shared by the vertex bake (transfer_bake.cpp) and the texel bake
// (texel_bake.cpp): the sample table, the rays of one receiver, and the pass itself over a
// list of receivers (points with unit normals), recording front-face hits for the bounces.
// Private to prt_transfer.
#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "baker/scene/scene.h"
#include "baker/transfer/embree_scene.h"
#include "baker/transfer/hit_record.h"
#include "baker/transfer/transfer_bake.h"
#include "prt/sampling.h"

namespace prt::bake {

// The shared sample directions and their basis values, coefficient-major.
struct SampleTable {
  DirectionSet dirs;
  std::vector<float> basis;        // [coefficient][sample]
  std::vector<float> sampleMajor;  // glossy bakes: the same, [sample][coefficient]
  // Visibility vectors for TPFL glossy (addVisibilityBasis): the basis at visibilityOrder,
  // [coefficient][sample]; empty when not asked for.
  int visibilityOrder = 0;
  std::vector<float> visibilityBasis;
};

// The direction set of `o` (Hammersley rotated by the seed, or stratified) and its basis.
Status makeSamples(const BakeOptions& o, SampleTable* t);

// Adds the basis of `order` (2..kMaxShOrder) at t's directions as t->visibilityBasis.
Status addVisibilityBasis(int order, SampleTable* t);

// Serialised progress callbacks for one pass, counting receivers and rays.
class ProgressReporter {
 public:
  ProgressReporter(const BakeOptions& o, std::string pass, std::size_t total)
      : o_(o), pass_(std::move(pass)), total_(total) {}
  void add(std::size_t receivers, std::uint64_t rays) {
    const std::size_t done = done_.fetch_add(receivers) + receivers;
    const std::uint64_t r = rays_.fetch_add(rays) + rays;
    if (o_.progress) {
      std::lock_guard<std::mutex> lock(mutex_);
      o_.progress({pass_.c_str(), done, total_, r});
    }
  }
  std::uint64_t rays() const { return rays_.load(); }

 private:
  const BakeOptions& o_;
  std::string pass_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::atomic<std::uint64_t> rays_{0};
  std::mutex mutex_;
};

double secondsSince(std::chrono::steady_clock::time_point t0);

// Rays of the direct pass for one receiver: one per sample direction w with n.w > 0 and
// horizon.w > 0, from `origin` (already offset along horizon). Writes the clamped-cosine
// weights w max(0, n.w)/pi of every sample (0 where no ray goes) and, per ray, its sample
// index. n is the shading normal, horizon the surface's (they differ under a normal map:
// light from below the surface's own tangent plane cannot reach it). With wholeHemisphere,
// every direction above the horizon is traced, those with n.w <= 0 at weight 0 (visibility).
unsigned fillRays(const SampleTable& table, Vec3 n, Vec3 horizon, Vec3 origin, float eps, RTCRayHit* rays,
                  std::uint32_t* sample, float* cosineWeight, bool wholeHemisphere = false);

// Ray origin offset and tnear, relative to the scene: far above float rounding of positions
// (~1e-7 of the extent), far below any feature the transfer can resolve.
float rayOffset(const EmbreeScene& embree);

// The bake options' and the scene's checks (ranges, sizes, indices, specular materials).
Status checkOptions(const Scene& scene, const BakeOptions& o);

// Per triangle, the unnormalised geometric normal cross(b - a, c - a) (winding decides the
// front face; its length is twice the area).
std::vector<Vec3> faceNormals(const Scene& scene);

// One direct pass over receivers [0, positions.size()), in blocks of kBlockVertices.
struct DirectPassJob {
  const EmbreeScene* embree = nullptr;
  const SampleTable* table = nullptr;
  const BakeOptions* options = nullptr;
  std::span<const Vec3> positions, normals;  // receivers: points on the surface, unit normals
  // Empty, or one per receiver: the unit shading normal of the cosine (a normal map's), with
  // `normals` still giving the horizon and the ray offset. Not with glossy.
  std::span<const Vec3> shadingNormals;
  std::span<const Vec3> faceNormal;          // faceNormals(scene)
  std::string name = "direct";               // progress and PassStats name
  unsigned threads = 1;
  float* unshadowed = nullptr;  // receivers x order^2
  float* shadowed = nullptr;    // receivers x order^2
  // Glossy (options->glossy): receivers x glossyEntries, packing matrixPackingFor(kShadowed, model).
  float* glossyShadowed = nullptr;
  std::size_t glossyEntries = 0;
  // TPFL (distant lighting, not glossy): receivers x table->visibilityOrder^2, the projection
  // of V(x, w) over the hemisphere above the horizon, no cosine: sum_k w V(x, w_k) y_i(w_k).
  float* visibility = nullptr;
  std::vector<HitBlock>* blocks = nullptr;  // with interreflection: one per receiver block, filled
  std::uint8_t* outside = nullptr;          // local lighting: per receiver, 1 outside the sphere S
};

// Runs `job` (deterministic whatever job.threads) and returns its stats; adds the glossy
// rank-update work to *kernelStats when glossy.
PassStats runDirectPass(const DirectPassJob& job, GlossyKernelStats* kernelStats);

}  // namespace prt::bake
