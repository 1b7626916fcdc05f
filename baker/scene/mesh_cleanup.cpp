#include "baker/scene/mesh_cleanup.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prt::bake {
namespace {

// Double precision so the area test measures the triangle, not float cancellation in it.
double lengthSquared(double x, double y, double z) { return x * x + y * y + z * z; }

bool isZeroArea(Vec3 a, Vec3 b, Vec3 c) {
  const double e1x = double{b.x} - a.x, e1y = double{b.y} - a.y, e1z = double{b.z} - a.z;
  const double e2x = double{c.x} - a.x, e2y = double{c.y} - a.y, e2z = double{c.z} - a.z;
  const double e3x = double{c.x} - b.x, e3y = double{c.y} - b.y, e3z = double{c.z} - b.z;
  const double cx = e1y * e2z - e1z * e2y, cy = e1z * e2x - e1x * e2z, cz = e1x * e2y - e1y * e2x;
  const double twiceArea = std::sqrt(lengthSquared(cx, cy, cz));
  const double longest2 =
      std::max({lengthSquared(e1x, e1y, e1z), lengthSquared(e2x, e2y, e2z), lengthSquared(e3x, e3y, e3z)});
  // Written so that NaN (overflowing corners) also counts as degenerate.
  return !(twiceArea > kDegenerateRelativeArea * longest2) || !std::isfinite(twiceArea);
}

}  // namespace

TriangleCleanupStats removeBadTriangles(std::span<const Vec3> positions, std::vector<std::uint32_t>* indices,
                                        std::vector<std::uint32_t>* triangleTags) {
  TriangleCleanupStats stats;
  std::vector<std::uint32_t>& idx = *indices;
  const std::size_t triangles = idx.size() / 3;
  const bool tagged = triangleTags != nullptr && triangleTags->size() == triangles;
  std::size_t kept = 0;
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t a = idx[3 * t], b = idx[3 * t + 1], c = idx[3 * t + 2];
    if (a >= positions.size() || b >= positions.size() || c >= positions.size()) {
      ++stats.outOfRange;
      continue;
    }
    if (!isFinite(positions[a]) || !isFinite(positions[b]) || !isFinite(positions[c])) {
      ++stats.nonFinite;
      continue;
    }
    if (isZeroArea(positions[a], positions[b], positions[c])) {
      ++stats.zeroArea;
      continue;
    }
    idx[3 * kept] = a;
    idx[3 * kept + 1] = b;
    idx[3 * kept + 2] = c;
    if (tagged) (*triangleTags)[kept] = (*triangleTags)[t];
    ++kept;
  }
  if (tagged) triangleTags->resize(kept);
  idx.resize(3 * kept);
  return stats;
}

std::size_t removeUnreferencedVertices(Scene* scene) {
  const std::size_t n = scene->positions.size();
  if (scene->normals.size() != n || scene->albedo.size() != n) return 0;
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> remap(n, kUnused);
  for (std::uint32_t v : scene->indices) {
    if (v < n) remap[v] = 0;
  }
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (remap[v] == kUnused) continue;
    remap[v] = next;
    scene->positions[next] = scene->positions[v];
    scene->normals[next] = scene->normals[v];
    scene->albedo[next] = scene->albedo[v];
    if (scene->pbr.size() == n) scene->pbr[next] = scene->pbr[v];
    if (scene->specular.size() == n) scene->specular[next] = scene->specular[v];
    for (std::vector<Uv>& uv : scene->texcoord) {
      if (uv.size() == n) uv[next] = uv[v];
    }
    if (scene->normalMapOf.size() == n) scene->normalMapOf[next] = scene->normalMapOf[v];
    if (scene->normalMapUv.size() == n) scene->normalMapUv[next] = scene->normalMapUv[v];
    if (scene->tangents.size() == n) scene->tangents[next] = scene->tangents[v];
    ++next;
  }
  scene->positions.resize(next);
  scene->normals.resize(next);
  scene->albedo.resize(next);
  if (scene->pbr.size() == n) scene->pbr.resize(next);
  if (scene->specular.size() == n) scene->specular.resize(next);
  for (std::vector<Uv>& uv : scene->texcoord) {
    if (uv.size() == n) uv.resize(next);
  }
  if (scene->normalMapOf.size() == n) scene->normalMapOf.resize(next);
  if (scene->normalMapUv.size() == n) scene->normalMapUv.resize(next);
  if (scene->tangents.size() == n) scene->tangents.resize(next);
  for (std::uint32_t& v : scene->indices) {
    if (v < n) v = remap[v];
  }
  return n - next;
}

}  // namespace prt::bake
