#include "baker/rtt/periodic_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "baker/scene/scene.h"

namespace prt::bake {

Status PeriodicTracer::build(const HeightPatch& patch, PeriodicTracer* out) {
  const int n = patch.size, side = 3 * n + 1;  // grid points a side over 3 x 3 periods
  Scene mesh;
  mesh.positions.reserve(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  out->gridPointOf_.clear();
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const std::uint32_t point = static_cast<std::uint32_t>((j % n) * n + (i % n));
      mesh.positions.push_back({static_cast<float>(i - n) / static_cast<float>(n), static_cast<float>(j - n) / static_cast<float>(n),
                                patch.height[point]});
      out->gridPointOf_.push_back(point);
    }
  }
  for (int j = 0; j + 1 < side; ++j) {
    for (int i = 0; i + 1 < side; ++i) {
      const auto a = static_cast<std::uint32_t>(j * side + i), b = a + 1, c = a + static_cast<std::uint32_t>(side) + 1,
                 d = a + static_cast<std::uint32_t>(side);
      mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});  // counter-clockwise seen from +z
    }
  }
  const auto [lo, hi] = std::minmax_element(patch.height.begin(), patch.height.end());
  out->minHeight_ = *lo;
  out->maxHeight_ = *hi;
  out->indices_ = mesh.indices;
  // Watertight: view rays pass exactly through grid points whenever a sample does.
  return EmbreeScene::build(mesh, &out->embree_, /*robust=*/true);
}

PeriodicHit PeriodicTracer::firstHit(Vec3 origin, Vec3 dir) const {
  PeriodicHit result;
  Vec3 o{origin.x - std::floor(origin.x), origin.y - std::floor(origin.y), origin.z};
  const float inf = std::numeric_limits<float>::infinity();
  // Far enough to cross the height range along z when the ray never leaves the period sideways.
  const float zSpan = (maxHeight_ - minHeight_) + 1.0f;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (int segment = 0; segment < 2 * kMaxPeriods; ++segment) {
    if (dir.z >= 0.0f && o.z > maxHeight_) return result;  // above everything, not descending
    const float tx = dir.x > 0.0f ? (1.0f - o.x) / dir.x : (dir.x < 0.0f ? -o.x / dir.x : inf);
    const float ty = dir.y > 0.0f ? (1.0f - o.y) / dir.y : (dir.y < 0.0f ? -o.y / dir.y : inf);
    const float tExit = std::max(0.0f, std::min(tx, ty));
    RTCRayHit rh{};
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = dir.x;
    rh.ray.dir_y = dir.y;
    rh.ray.dir_z = dir.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::isfinite(tExit) ? tExit : zSpan / std::max(std::fabs(dir.z), 1e-6f);
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_.handle(), &context, &rh);
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      result.hit = true;
      result.triangle = rh.hit.primID;
      result.u = rh.hit.u;
      result.v = rh.hit.v;
      return result;
    }
    if (!std::isfinite(tExit)) return result;
    // Into the next period: continue from the exit point, moved back across the seam it crossed.
    o = o + dir * tExit;
    if (tx <= ty) o.x = dir.x > 0.0f ? 0.0f : 1.0f;
    if (ty <= tx) o.y = dir.y > 0.0f ? 0.0f : 1.0f;
  }
  return result;
}

PeriodicHit PeriodicTracer::viewHit(Vec3 point, Vec3 toViewer) const {
  // Start just above the patch on the line through `point`.
  const float up = std::max(0.0f, maxHeight_ - point.z) + 1e-3f;
  const Vec3 start = point + toViewer * (up / std::max(toViewer.z, 1e-6f));
  return firstHit(start, toViewer * -1.0f);
}

void PeriodicTracer::interpolate(const PeriodicHit& hit, const std::vector<float>& perPoint, std::size_t stride, float* out) const {
  const std::size_t t = static_cast<std::size_t>(hit.triangle) * 3;
  const float* p0 = &perPoint[gridPointOf_[indices_[t]] * stride];
  const float* p1 = &perPoint[gridPointOf_[indices_[t + 1]] * stride];
  const float* p2 = &perPoint[gridPointOf_[indices_[t + 2]] * stride];
  const float w0 = 1.0f - hit.u - hit.v;
  for (std::size_t q = 0; q < stride; ++q) out[q] = w0 * p0[q] + hit.u * p1[q] + hit.v * p2[q];
}

std::vector<std::size_t> PeriodicTracer::triangleGridPoints(const PeriodicHit& hit) const {
  const std::size_t t = static_cast<std::size_t>(hit.triangle) * 3;
  return {gridPointOf_[indices_[t]], gridPointOf_[indices_[t + 1]], gridPointOf_[indices_[t + 2]]};
}

}  // namespace prt::bake
