#include "baker/transfer/glossy_reference.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "baker/transfer/embree_scene.h"
#include "baker/transfer/local_sphere.h"
#include "baker/transfer/parallel_for.h"
#include "baker/transfer/reference_sampling.h"
#include "prt/glossy_lobe.h"
#include "prt/sampling.h"

namespace prt::bake {
namespace {

constexpr std::size_t kRayBatch = 1024;

using reference::frameAround;
using reference::radicalInverse2;

}  // namespace

Status glossyReferenceRadiance(const Scene& scene, std::span<const std::uint32_t> vertices, Vec3 eye,
                               const LightingInfo& lighting, const RadianceFunction& radiance,
                               const GlossyReferenceOptions& o, std::vector<Rgb>* out) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "glossy reference: output is null");
  if (!radiance) return Status::error(StatusCode::kInvalidArgument, "glossy reference: radiance function is empty");
  if (o.samples < 1 || o.samples > (std::size_t{1} << 24)) {
    return Status::error(StatusCode::kInvalidArgument,
                         "glossy reference sample count " + std::to_string(o.samples) + " is outside [1, 2^24]");
  }
  if (!isFinite(eye)) return Status::error(StatusCode::kInvalidArgument, "glossy reference: eye is not finite");
  if (Status s = checkLightingInfo(lighting); !s.isOk())
    return Status::error(s.code(), "glossy reference " + s.message());
  if (lighting.model == LightingModel::kLocalSpherePaper) {
    return Status::error(StatusCode::kInvalidArgument,
                         "glossy reference: local-sphere-paper lighting is not a radiance; use local-sphere");
  }
  const std::size_t vertexCount = scene.positions.size();
  if (scene.normals.size() != vertexCount || scene.specular.size() != vertexCount) {
    return Status::error(StatusCode::kSizeMismatch,
                         "glossy reference: scene normals/specular do not match its positions");
  }
  for (std::uint32_t v : vertices) {
    if (v >= vertexCount)
      return Status::error(StatusCode::kInvalidArgument, "glossy reference: vertex index out of range");
    const SpecularMaterial& m = scene.specular[v];
    if (!(m.exponent >= 0.0f) || !std::isfinite(m.exponent)) {
      return Status::error(StatusCode::kInvalidArgument, "glossy reference: specular exponent negative or not finite");
    }
  }
  EmbreeScene embree;
  if (Status s = EmbreeScene::build(scene, &embree); !s.isOk()) return s;
  const float eps = 1e-5f * std::max(embree.diagonal(), 1e-6f);  // transfer_bake.cpp rayOffset
  const bool local = isLocalLighting(lighting.model);
  double shiftU = 0.0, shiftV = 0.0;
  if (o.seed != 0) {
    Pcg32 rng(o.seed);
    shiftU = rng.nextFloat();
    shiftV = rng.nextFloat();
  }
  out->assign(vertices.size(), Rgb{});
  const unsigned threads = o.threads ? o.threads : defaultThreadCount();
  struct Scratch {
    std::vector<RTCRay> rays;
    std::vector<Vec3> lookup;
  };
  std::vector<Scratch> scratch(threads);
  for (auto& s : scratch) {
    s.rays.resize(kRayBatch);
    s.lookup.resize(kRayBatch);
  }
  parallelFor(vertices.size(), threads, [&](std::size_t index, unsigned thread) {
    Scratch& s = scratch[thread];
    const std::uint32_t vertex = vertices[index];
    const Vec3 x = scene.positions[vertex], n = scene.normals[vertex];
    const SpecularMaterial& mat = scene.specular[vertex];
    const Vec3 toEye = eye - x;
    const float d = length(toEye);
    if (!(d > 0.0f)) return;
    const Vec3 v = toEye * (1.0f / d);
    const Vec3 R = reflectView(v, n);
    Vec3 t1, t2;
    frameAround(R, &t1, &t2);
    const SpherePoint sp = local ? locateOnSphere(x, lighting.center, lighting.radius) : SpherePoint{};
    const Vec3 origin = x + n * eps;
    const double invExp = 1.0 / (static_cast<double>(mat.exponent) + 1.0);
    double sum[3] = {0, 0, 0};
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::size_t m0 = 0; m0 < o.samples; m0 += kRayBatch) {
      const std::size_t batch = std::min(kRayBatch, o.samples - m0);
      std::size_t count = 0;
      for (std::size_t m = m0; m < m0 + batch; ++m) {
        double u = (static_cast<double>(m) + 0.5) / static_cast<double>(o.samples) + shiftU;
        double w2 = radicalInverse2(static_cast<std::uint32_t>(m)) + shiftV;
        u -= std::floor(u);
        w2 -= std::floor(w2);
        // Inverse CDF of the lobe: P(cos <= c) = c^(s+1) on [0, 1].
        const double cosT = std::pow(u, invExp), sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
        const double phi = 2.0 * kPi * w2;
        Vec3 w = t1 * static_cast<float>(sinT * std::cos(phi)) + t2 * static_cast<float>(sinT * std::sin(phi)) +
                 R * static_cast<float>(cosT);
        w = w * (1.0f / length(w));
        if (!(dot(n, w) > 0.0f)) continue;  // V = 0 below the tangent plane
        float tFar = INFINITY;
        Vec3 look = w;
        if (local) {
          const float t = exitDistance(sp, w);
          if (!(t > 0.0f)) continue;  // never reaches S: no light
          tFar = t;
          look = (sp.p + w * t) * sp.invRadius;
          look = look * (1.0f / length(look));
        }
        RTCRay& r = s.rays[count];
        r.org_x = origin.x;
        r.org_y = origin.y;
        r.org_z = origin.z;
        r.tnear = eps;
        r.dir_x = w.x;
        r.dir_y = w.y;
        r.dir_z = w.z;
        r.time = 0.0f;
        r.tfar = tFar;
        r.mask = 0xFFFFFFFFu;
        r.id = 0;
        r.flags = 0;
        s.lookup[count] = look;
        ++count;
      }
      if (count > 0)
        rtcOccluded1M(embree.handle(), &context, s.rays.data(), static_cast<unsigned>(count), sizeof(RTCRay));
      for (std::size_t j = 0; j < count; ++j) {
        if (s.rays[j].tfar < 0.0f) continue;  // occluded
        const Rgb L = radiance(s.lookup[j]);
        sum[0] += L.r;
        sum[1] += L.g;
        sum[2] += L.b;
      }
    }
    const Rgb ks = o.includeFresnel ? schlickFresnel(mat.f0, mat.f90, dot(n, v)) : mat.f0;
    const double inv = 1.0 / static_cast<double>(o.samples);
    (*out)[index] = Rgb{static_cast<float>(ks.r * sum[0] * inv), static_cast<float>(ks.g * sum[1] * inv),
                        static_cast<float>(ks.b * sum[2] * inv)};
  });
  return Status::ok();
}

}  // namespace prt::bake
