#include "baker/transfer/local_sphere.h"

#include <algorithm>
#include <cmath>

namespace prt::bake {

SpherePoint locateOnSphere(Vec3 x, Vec3 center, float radius) {
  SpherePoint s;
  s.p = x - center;
  // Double: |p|^2 and r^2 cancel for points on S, whose classification is the point here.
  const double px = s.p.x, py = s.p.y, pz = s.p.z, r = radius;
  const double delta = r * r - (px * px + py * py + pz * pz);
  const double onSurface = 1e-6 * r * r;
  s.outside = delta < -onSurface;
  s.delta = static_cast<float>(s.outside ? delta : std::max(delta, 0.0));
  s.radius = radius;
  s.invRadius = 1.0f / radius;
  return s;
}

float exitDistance(const SpherePoint& s, Vec3 w) {
  // |p + t w|^2 = r^2  <=>  t^2 + 2 b t - delta = 0 with b = p.w: t = -b +- sqrt(b^2 + delta).
  const float b = dot(s.p, w);
  const float disc = b * b + s.delta;
  if (disc < 0.0f) return -1.0f;  // outside S and the line misses it
  const float root = std::sqrt(disc);
  if (b <= 0.0f) return root - b;  // -b + root, no cancellation
  // b > 0: -b + root cancels; delta / (b + root) is the same value computed stably. Outside
  // S (delta < 0) it is negative: the sphere is behind the ray.
  return s.delta / (b + root);
}

RemappedRay remapRay(const SpherePoint& s, Vec3 w, LightingModel model) {
  RemappedRay r;
  const float t = exitDistance(s, w);
  if (!(t >= 0.0f)) {
    r.lightDir = w;
    r.tFar = INFINITY;
    return r;
  }
  r.reachesLight = true;
  r.tFar = t;
  // At x = c: p = 0 and t = sqrt(r^2) = r exactly (IEEE square roots are correctly rounded),
  // so t / r = 1 and w' = w bit for bit: the local transfer there is the distant one.
  r.lightDir = s.p * s.invRadius + w * (t / s.radius);
  r.weight = 1.0f;
  if (model == LightingModel::kLocalSpherePaper) {
    // cos(theta') between S's inward normal -w' and the direction -w back to x.
    r.weight = 1.0f / std::max(dot(w, r.lightDir), kPaperMinCosine);
  }
  return r;
}

LightingInfo defaultLightingSphere(const Scene& scene, LightingModel model) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const Vec3& x : scene.positions) {
    const double v[3] = {x.x, x.y, x.z};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], v[a]), hi[a] = std::max(hi[a], v[a]);
  }
  LightingInfo l;
  l.model = model;
  if (scene.positions.empty()) {
    l.radius = 1.0f;
    return l;
  }
  l.center = {static_cast<float>(0.5 * (lo[0] + hi[0])), static_cast<float>(0.5 * (lo[1] + hi[1])),
              static_cast<float>(0.5 * (lo[2] + hi[2]))};
  const double half = 0.5 * std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                      (hi[2] - lo[2]) * (hi[2] - lo[2]));
  l.radius = half > 0.0 ? static_cast<float>(half) : 1.0f;
  return l;
}

}  // namespace prt::bake
