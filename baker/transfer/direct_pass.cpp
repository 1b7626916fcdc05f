#include "baker/transfer/direct_pass.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <memory>
#include <utility>

#include "baker/transfer/glossy_bake.h"
#include "baker/transfer/local_sphere.h"
#include "baker/transfer/sh_accumulate.h"
#include "baker/transfer/parallel_for.h"
#include "prt/sh_basis.h"

namespace prt::bake {

Status makeSamples(const BakeOptions& o, SampleTable* t) {
  if (o.sampling == Sampling::kStratified) {
    const auto side = static_cast<std::size_t>(std::lround(std::sqrt(static_cast<double>(o.samples))));
    if (side * side != o.samples) {
      return Status::error(StatusCode::kInvalidArgument,
                           "stratified sampling needs a square sample count (got " + std::to_string(o.samples) + ")");
    }
    if (Status s = stratifiedSphere(side, o.seed, &t->dirs); !s.isOk()) return s;
  } else {
    if (Status s = hammersleySphere(o.samples, &t->dirs); !s.isOk()) return s;
    if (o.seed != 0) {
      // A seeded rotation of the whole set: a new, equally well-distributed set per seed.
      Pcg32 rng(o.seed);
      const Vec3 axis = squareToSphere(rng.nextFloat(), rng.nextFloat());
      const Mat3 r = rotationAxisAngle(axis, static_cast<float>(2.0 * kPi) * rng.nextFloat());
      for (std::size_t k = 0; k < t->dirs.size(); ++k) {
        Vec3 d = r * t->dirs.at(k);
        d = d * (1.0f / length(d));
        t->dirs.x[k] = d.x;
        t->dirs.y[k] = d.y;
        t->dirs.z[k] = d.z;
      }
    }
  }
  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(o.order)), count = t->dirs.size();
  t->basis.resize(n2 * count);
  if (Status s = evalShBasisBatch(o.order, t->dirs.x, t->dirs.y, t->dirs.z, t->basis); !s.isOk()) return s;
  if (o.glossy) {
    t->sampleMajor.resize(n2 * count);
    for (std::size_t i = 0; i < n2; ++i) {
      for (std::size_t k = 0; k < count; ++k) t->sampleMajor[k * n2 + i] = t->basis[i * count + k];
    }
  }
  return Status::ok();
}

Status addVisibilityBasis(int order, SampleTable* t) {
  if (order < 2 || order > kMaxShOrder) {
    return Status::error(StatusCode::kInvalidArgument,
                         "visibility order " + std::to_string(order) + " is outside [2, " + std::to_string(kMaxShOrder) + "]");
  }
  t->visibilityOrder = order;
  t->visibilityBasis.resize(static_cast<std::size_t>(shCoeffCount(order)) * t->dirs.size());
  return evalShBasisBatch(order, t->dirs.x, t->dirs.y, t->dirs.z, t->visibilityBasis);
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

unsigned fillRays(const SampleTable& table, Vec3 n, Vec3 horizon, Vec3 origin, float eps, RTCRayHit* rays,
                  std::uint32_t* sample, float* cosineWeight, bool wholeHemisphere) {
  const std::size_t sampleCount = table.dirs.size();
  const float sampleWeight = static_cast<float>(table.dirs.weight / kPi);
  unsigned count = 0;
  for (std::size_t k = 0; k < sampleCount; ++k) {
    const float c = n.x * table.dirs.x[k] + n.y * table.dirs.y[k] + n.z * table.dirs.z[k];
    const float above = horizon.x * table.dirs.x[k] + horizon.y * table.dirs.y[k] + horizon.z * table.dirs.z[k];
    const bool lit = c > 0.0f && above > 0.0f;
    const bool traced = wholeHemisphere ? above > 0.0f : lit;
    cosineWeight[k] = lit ? c * sampleWeight : 0.0f;
    if (!traced) continue;
    RTCRayHit& r = rays[count];
    r.ray.org_x = origin.x;
    r.ray.org_y = origin.y;
    r.ray.org_z = origin.z;
    r.ray.tnear = eps;
    r.ray.dir_x = table.dirs.x[k];
    r.ray.dir_y = table.dirs.y[k];
    r.ray.dir_z = table.dirs.z[k];
    r.ray.time = 0.0f;
    r.ray.tfar = INFINITY;
    r.ray.mask = 0xFFFFFFFFu;
    r.ray.id = 0;
    r.ray.flags = 0;
    r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    r.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    sample[count] = static_cast<std::uint32_t>(k);
    ++count;
  }
  return count;
}

// Offsets relative to the scene: far above float rounding of positions (~1e-7 of the
// extent), far below any feature the transfer can resolve.
float rayOffset(const EmbreeScene& embree) { return 1e-5f * std::max(embree.diagonal(), 1e-6f); }

Status checkOptions(const Scene& scene, const BakeOptions& o) {
  if (o.order < 2 || o.order > 8) {
    return Status::error(StatusCode::kInvalidArgument, "bake order " + std::to_string(o.order) + " is outside [2, 8]");
  }
  if (o.samples < 16 || o.samples > (1u << 20)) {
    return Status::error(StatusCode::kInvalidArgument,
                         "sample count " + std::to_string(o.samples) + " is outside [16, 1048576]");
  }
  if (o.maxBounces < 0 || o.maxBounces > 64) {
    return Status::error(StatusCode::kInvalidArgument, "bounce count must be in [0, 64]");
  }
  if (Status s = checkLightingInfo(o.lighting); !s.isOk()) return Status::error(s.code(), "bake " + s.message());
  if (o.glossy && (o.glossyBounces < 0 || o.glossyBounces > o.maxBounces)) {
    return Status::error(StatusCode::kInvalidArgument, "glossy bounce count " + std::to_string(o.glossyBounces) +
                                                           " is outside [0, maxBounces = " +
                                                           std::to_string(o.maxBounces) + "]");
  }
  if (o.glossy && o.glossyBounces > 0 && !o.interreflection) {
    return Status::error(StatusCode::kInvalidArgument,
                         "glossy bounces need interreflection (set glossyBounces to 0 or enable interreflection)");
  }
  const std::size_t vertexCount = scene.positions.size();
  if (scene.normals.size() != vertexCount || scene.albedo.size() != vertexCount) {
    return Status::error(StatusCode::kSizeMismatch, "scene normals/albedo do not match its positions");
  }
  if (!scene.specular.empty() && scene.specular.size() != vertexCount) {
    return Status::error(StatusCode::kSizeMismatch, "scene specular materials do not match its positions");
  }
  for (const SpecularMaterial& m : scene.specular) {
    const float f[4] = {m.f0.r, m.f0.g, m.f0.b, m.f90};
    for (float x : f) {
      if (!(x >= 0.0f && x <= 1.0f)) return Status::error(StatusCode::kInvalidArgument, "scene specular f0 or f90 outside [0, 1]");
    }
    if (!(m.exponent >= 0.0f) || !std::isfinite(m.exponent)) {
      return Status::error(StatusCode::kInvalidArgument, "scene specular exponent is negative or not finite");
    }
  }
  for (std::uint32_t index : scene.indices) {
    if (index >= vertexCount) return Status::error(StatusCode::kInvalidArgument, "scene index out of range");
  }
  return Status::ok();
}

std::vector<Vec3> faceNormals(const Scene& scene) {
  std::vector<Vec3> faceNormal(scene.indices.size() / 3);
  for (std::size_t t = 0; t < faceNormal.size(); ++t) {
    const Vec3 a = scene.positions[scene.indices[3 * t]], b = scene.positions[scene.indices[3 * t + 1]],
               c = scene.positions[scene.indices[3 * t + 2]];
    faceNormal[t] = cross(b - a, c - a);
  }
  return faceNormal;
}

PassStats runDirectPass(const DirectPassJob& job, GlossyKernelStats* kernelStats) {
  const BakeOptions& o = *job.options;
  const int n2 = shCoeffCount(o.order);
  const std::size_t sampleCount = job.table->dirs.size();
  const std::size_t receiverCount = job.positions.size();
  const std::size_t blockCount = (receiverCount + kBlockVertices - 1) / kBlockVertices;
  const std::size_t glossyEntries = job.glossyEntries;
  const float eps = rayOffset(*job.embree);
  const unsigned threads = std::max(1u, job.threads);
  if (job.blocks) job.blocks->assign(blockCount, HitBlock{});
  const auto t0 = std::chrono::steady_clock::now();
  ProgressReporter progress(o, job.name, receiverCount);
  const bool local = isLocalLighting(o.lighting.model);
  struct Scratch {
    std::vector<RTCRayHit> rays;
    std::vector<std::uint32_t> sample;
    std::vector<float> unshadowedW, shadowedW;  // per sample k; solid-angle weights w max(0, n.w)/pi
    // Local lighting, per ray j: w'_j, the lit weights (solid angle x remap weight, 0 for rays
    // that never reach S) and the basis at w'_j, [coefficient][ray].
    std::vector<float> lightX, lightY, lightZ, litUnshadowed, litShadowed, basis;
    // Glossy: visible sample indices (distant) or per-ray weights w q V (local), no cosine.
    std::vector<std::uint32_t> visible;
    std::vector<float> litGlossy;
    std::vector<float> visibleW;  // TPFL: per sample k, w V(x, w_k) above the horizon
    // The block's hit records while it runs (HitBlock's fields).
    std::vector<Hit> hits;
    std::vector<std::uint32_t> hitSample, hitStart;
    std::unique_ptr<GlossyShadowedKernel> kernel;
    GlossyKernelStats kernelStats;
  };
  std::vector<Scratch> scratch(threads);
  for (auto& s : scratch) {
    s.rays.resize(sampleCount);
    s.sample.resize(sampleCount);
    s.unshadowedW.resize(sampleCount);
    s.shadowedW.resize(sampleCount);
    if (local) {
      for (auto* a : {&s.lightX, &s.lightY, &s.lightZ, &s.litUnshadowed, &s.litShadowed}) a->resize(sampleCount);
      s.basis.resize(static_cast<std::size_t>(n2) * sampleCount);
    }
    if (o.glossy) {
      s.visible.resize(sampleCount);
      s.litGlossy.resize(sampleCount);
      s.kernel = std::make_unique<GlossyShadowedKernel>(o.order, sampleCount);
    }
    if (job.visibility) s.visibleW.resize(sampleCount);
  }
  // Callers check this (texel_bake.cpp): TPFL's product needs one basis for light and view.
  assert(!job.visibility || (!local && !o.glossy && job.table->visibilityOrder >= 2));
  parallelFor(blockCount, threads, [&](std::size_t block, unsigned thread) {
    Scratch& s = scratch[thread];
    const std::size_t begin = block * kBlockVertices, end = std::min(receiverCount, begin + kBlockVertices);
    HitBlock* rec = job.blocks ? &(*job.blocks)[block] : nullptr;
    if (rec) {
      s.hits.clear();
      s.hitSample.clear();
      s.hitStart.assign(1, 0);
    }
    std::uint64_t rays = 0;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // One origin, many directions: a fan, not a beam. Handed to Embree as a coherent stream
    // (rtcIntersect1M) it is packed into packets whose rays diverge at once, which traced at
    // 0.6x the rate of the same rays one at a time (docs/bench/bake-dragon.md).
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    for (std::size_t v = begin; v < end; ++v) {
      if (job.visibility) std::fill(s.visibleW.begin(), s.visibleW.end(), 0.0f);
      const Vec3 n = job.normals[v];
      const Vec3 origin = job.positions[v] + n * eps;
      const Vec3 shading = job.shadingNormals.empty() ? n : job.shadingNormals[v];
      const unsigned count = fillRays(*job.table, shading, n, origin, eps, s.rays.data(), s.sample.data(),
                                      s.unshadowedW.data(), job.visibility != nullptr);
      if (local) {
        const SpherePoint sp = locateOnSphere(job.positions[v], o.lighting.center, o.lighting.radius);
        if (job.outside) job.outside[v] = sp.outside;
        for (unsigned j = 0; j < count; ++j) {
          RTCRay& ray = s.rays[j].ray;
          const RemappedRay m = remapRay(sp, Vec3{ray.dir_x, ray.dir_y, ray.dir_z}, o.lighting.model);
          ray.tfar = m.tFar;  // occluders beyond S are part of the lighting, not the scene
          s.lightX[j] = m.lightDir.x;
          s.lightY[j] = m.lightDir.y;
          s.lightZ[j] = m.lightDir.z;
          s.litUnshadowed[j] = s.litShadowed[j] = s.unshadowedW[s.sample[j]] * m.weight;
          if (o.glossy) s.litGlossy[j] = static_cast<float>(job.table->dirs.weight) * m.weight;
        }
      } else {
        std::copy(s.unshadowedW.begin(), s.unshadowedW.end(), s.shadowedW.begin());
      }
      if (rec) {
        for (unsigned j = 0; j < count; ++j) rtcIntersect1(job.embree->handle(), &context, &s.rays[j]);
      } else {
        for (unsigned j = 0; j < count; ++j) rtcOccluded1(job.embree->handle(), &context, &s.rays[j].ray);
      }
      rays += count;
      std::size_t visibleCount = 0;
      for (unsigned j = 0; j < count; ++j) {
        const RTCRayHit& r = s.rays[j];
        const bool blocked = rec ? r.hit.geomID != RTC_INVALID_GEOMETRY_ID : r.ray.tfar < 0.0f;
        if (!blocked) {
          if (o.glossy) s.visible[visibleCount++] = s.sample[j];
          if (job.visibility) s.visibleW[s.sample[j]] = static_cast<float>(job.table->dirs.weight);
          continue;
        }
        const std::uint32_t k = s.sample[j];
        if (local) {
          s.litShadowed[j] = 0.0f;
          if (o.glossy) s.litGlossy[j] = 0.0f;
        } else {
          s.shadowedW[k] = 0.0f;
        }
        // Hits keep the solid-angle weight in both models: a bounce gathers radiance over
        // directions at x from surfaces inside S, which does not involve the remapping.
        // (A ray traced for visibility only has cosine weight 0: it gathers nothing.)
        if (rec && s.unshadowedW[k] > 0.0f &&
            dot(job.faceNormal[r.hit.primID], Vec3{r.ray.dir_x, r.ray.dir_y, r.ray.dir_z}) < 0.0f) {
          auto unorm = [](float x) { return static_cast<std::uint16_t>(std::lround(std::clamp(x, 0.0f, 1.0f) * 65535.0f)); };
          s.hits.push_back({r.hit.primID, unorm(r.hit.u), unorm(r.hit.v), s.unshadowedW[k]});
          if (o.glossy) s.hitSample.push_back(k);
        }
      }
      if (rec) s.hitStart.push_back(static_cast<std::uint32_t>(s.hits.size()));
      if (local) {
        // One basis evaluation per ray, batched over the vertex's rays (the distant bake
        // evaluates each sample's basis once for all vertices).
        evalShBasisBatchUnchecked(o.order, count, s.lightX.data(), s.lightY.data(), s.lightZ.data(), s.basis.data());
        projectWeights(n2, count, s.litUnshadowed.data(), s.basis.data(), &job.unshadowed[v * n2]);
        projectWeights(n2, count, s.litShadowed.data(), s.basis.data(), &job.shadowed[v * n2]);
        if (o.glossy) {
          s.kernel->local(job.table->sampleMajor.data(), s.sample.data(), s.litGlossy.data(), count, s.basis.data(),
                          &job.glossyShadowed[v * glossyEntries], &s.kernelStats);
        }
      } else {
        projectWeights(n2, sampleCount, s.unshadowedW.data(), job.table->basis.data(), &job.unshadowed[v * n2]);
        projectWeights(n2, sampleCount, s.shadowedW.data(), job.table->basis.data(), &job.shadowed[v * n2]);
        if (job.visibility) {
          const int m2 = shCoeffCount(job.table->visibilityOrder);
          projectWeights(m2, sampleCount, s.visibleW.data(), job.table->visibilityBasis.data(),
                         &job.visibility[v * static_cast<std::size_t>(m2)]);
        }
        if (o.glossy) {
          s.kernel->distant(job.table->sampleMajor.data(), s.visible.data(), visibleCount,
                            static_cast<float>(job.table->dirs.weight), &job.glossyShadowed[v * glossyEntries],
                            &s.kernelStats);
        }
      }
    }
    if (rec) {
      // Copied out at their exact size: grown in place, a block's records kept up to twice
      // their bytes in capacity, and they are most of a big bake's memory.
      rec->hits.assign(s.hits.begin(), s.hits.end());
      rec->hitSample.assign(s.hitSample.begin(), s.hitSample.end());
      rec->hitStart.assign(s.hitStart.begin(), s.hitStart.end());
    }
    progress.add(end - begin, rays);
  });

  for (const Scratch& s : scratch) {  // thread order: the sums of flops are exact, seconds are timings
    kernelStats->flops += s.kernelStats.flops;
    kernelStats->threadSeconds += s.kernelStats.threadSeconds;
  }
  return {job.name, secondsSince(t0), progress.rays()};
}

}  // namespace prt::bake
