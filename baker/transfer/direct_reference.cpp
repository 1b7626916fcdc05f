#include "baker/transfer/direct_reference.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "baker/transfer/embree_scene.h"
#include "baker/transfer/parallel_for.h"
#include "baker/transfer/reference_sampling.h"
#include "prt/sampling.h"
#include "prt/sh_basis.h"
#include "prt/sh_zonal.h"

namespace prt::bake {
namespace {

constexpr std::size_t kBlockVertices = 16;
constexpr std::size_t kRayBatch = 1024;

using reference::frameAround;
using reference::radicalInverse2;

Status checkCap(const CapEmitter& cap) {
  if (!isFinite(cap.center) || !std::isfinite(cap.radius) || !(cap.radius > 0.0f)) {
    return Status::error(StatusCode::kInvalidArgument, "cap emitter: centre must be finite and radius finite and > 0");
  }
  if (!isFinite(cap.axis) || !(length(cap.axis) > 0.0f)) {
    return Status::error(StatusCode::kInvalidArgument, "cap emitter: axis must be finite and non-zero");
  }
  if (!(cap.halfAngle > 0.0f) || cap.halfAngle > static_cast<float>(kPi)) {
    return Status::error(StatusCode::kInvalidArgument, "cap emitter: half-angle must be in (0, pi]");
  }
  if (!std::isfinite(cap.radiance)) return Status::error(StatusCode::kInvalidArgument, "cap emitter: radiance must be finite");
  return Status::ok();
}

}  // namespace

Status directIrradianceFromCap(const Scene& scene, const CapEmitter& cap, const DirectReferenceOptions& o,
                               std::vector<double>* irradiance) {
  if (irradiance == nullptr) return Status::error(StatusCode::kInvalidArgument, "directIrradianceFromCap: output is null");
  if (Status s = checkCap(cap); !s.isOk()) return s;
  if (o.samples < 1 || o.samples > (std::size_t{1} << 24)) {
    return Status::error(StatusCode::kInvalidArgument, "reference sample count " + std::to_string(o.samples) + " is outside [1, 2^24]");
  }
  const std::size_t vertexCount = scene.positions.size();
  if (scene.normals.size() != vertexCount) return Status::error(StatusCode::kSizeMismatch, "scene normals do not match its positions");
  EmbreeScene embree;
  if (Status s = EmbreeScene::build(scene, &embree); !s.isOk()) return s;
  // The bake's offset (transfer_bake.cpp rayOffset): same scale, same self-intersection margin.
  const float eps = 1e-5f * std::max(embree.diagonal(), 1e-6f);

  // Emitter points, the same set for every vertex: uniform by area on the cap means
  // cos(gamma) uniform in [cos(halfAngle), 1] and azimuth uniform.
  const Vec3 axis = cap.axis * (1.0f / length(cap.axis));
  Vec3 t1, t2;
  frameAround(axis, &t1, &t2);
  double shiftU = 0.0, shiftV = 0.0;
  if (o.seed != 0) {
    Pcg32 rng(o.seed);
    shiftU = rng.nextFloat();
    shiftV = rng.nextFloat();
  }
  const double cosMax = std::cos(static_cast<double>(cap.halfAngle));
  std::vector<Vec3> points(o.samples), inward(o.samples);
  std::vector<double> pointRadiance(o.samples, 1.0);
  for (std::size_t k = 0; k < o.samples; ++k) {
    const double u = std::fmod((k + 0.5) / static_cast<double>(o.samples) + shiftU, 1.0);
    const double v = std::fmod(radicalInverse2(static_cast<std::uint32_t>(k)) + shiftV, 1.0);
    const double cosGamma = 1.0 - u * (1.0 - cosMax);
    const double sinGamma = std::sqrt(std::max(0.0, 1.0 - cosGamma * cosGamma));
    const double phi = 2.0 * kPi * v;
    const Vec3 d = t1 * static_cast<float>(sinGamma * std::cos(phi)) + t2 * static_cast<float>(sinGamma * std::sin(phi)) +
                   axis * static_cast<float>(cosGamma);
    points[k] = cap.center + d * cap.radius;
    inward[k] = d * -1.0f;
    if (cap.radianceAt) pointRadiance[k] = cap.radianceAt(d);
  }
  const double area = 2.0 * kPi * static_cast<double>(cap.radius) * cap.radius * (1.0 - cosMax);
  const double pointWeight = area / static_cast<double>(o.samples) * cap.radiance;

  irradiance->assign(vertexCount, 0.0);
  const unsigned threads = o.threads ? o.threads : defaultThreadCount();
  const std::size_t blockCount = (vertexCount + kBlockVertices - 1) / kBlockVertices;
  struct Scratch {
    std::vector<RTCRay> rays;
    std::vector<double> geometry;  // max(0, n.w) cos(theta_y) / d^2 per ray
  };
  std::vector<Scratch> scratch(threads);
  for (Scratch& s : scratch) {
    s.rays.resize(kRayBatch);
    s.geometry.resize(kRayBatch);
  }
  parallelFor(blockCount, threads, [&](std::size_t block, unsigned thread) {
    Scratch& s = scratch[thread];
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    const std::size_t begin = block * kBlockVertices, end = std::min(vertexCount, begin + kBlockVertices);
    for (std::size_t v = begin; v < end; ++v) {
      const Vec3 x = scene.positions[v], n = scene.normals[v];
      const Vec3 origin = x + n * eps;
      double sum = 0.0;
      std::size_t k = 0;
      while (k < o.samples) {
        unsigned count = 0;
        for (; k < o.samples && count < kRayBatch; ++k) {
          const Vec3 toY = points[k] - x;
          const double d2 = static_cast<double>(dot(toY, toY));
          if (!(d2 > 0.0)) continue;
          const double d = std::sqrt(d2);
          const Vec3 w = toY * static_cast<float>(1.0 / d);
          const double cosX = dot(n, w);
          const double cosY = -static_cast<double>(dot(inward[k], w));  // emitter normal faces -w back to x
          if (cosX <= 0.0 || cosY <= 0.0) continue;
          RTCRay& r = s.rays[count];
          r.org_x = origin.x;
          r.org_y = origin.y;
          r.org_z = origin.z;
          r.dir_x = w.x;
          r.dir_y = w.y;
          r.dir_z = w.z;
          r.tnear = eps;
          r.tfar = std::max(eps, static_cast<float>(d) - eps);
          r.time = 0.0f;
          r.mask = 0xFFFFFFFFu;
          r.id = 0;
          r.flags = 0;
          s.geometry[count] = pointRadiance[k] * cosX * cosY / d2;
          ++count;
        }
        if (count == 0) continue;
        rtcOccluded1M(embree.handle(), &context, s.rays.data(), count, sizeof(RTCRay));
        for (unsigned j = 0; j < count; ++j) {
          if (s.rays[j].tfar >= 0.0f) sum += s.geometry[j];
        }
      }
      (*irradiance)[v] = sum * pointWeight;
    }
  });
  return Status::ok();
}

Status capLightingSh(const CapEmitter& cap, int order, std::vector<float>* coeffs) {
  if (coeffs == nullptr) return Status::error(StatusCode::kInvalidArgument, "capLightingSh: output is null");
  if (Status s = checkCap(cap); !s.isOk()) return s;
  if (cap.radianceAt) return Status::error(StatusCode::kInvalidArgument, "capLightingSh: only uniform caps have a closed form");
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  std::vector<float> zonal(static_cast<std::size_t>(order));
  if (Status s = zonalCircularLight(order, cap.halfAngle, cap.radiance, zonal); !s.isOk()) return s;
  coeffs->assign(static_cast<std::size_t>(shCoeffCount(order)), 0.0f);
  return placeZonal(order, zonal, cap.axis, *coeffs);
}

}  // namespace prt::bake
