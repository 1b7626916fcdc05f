#include "baker/scene/mesh_normals.h"

#include <cmath>

namespace prt::bake {
namespace {

// Accumulation runs in double: a vertex shared by thousands of triangles (a fan pole) sums
// thousands of terms, and float sums of nearly cancelling terms lose the direction.
struct D3 {
  double x = 0, y = 0, z = 0;
};

D3 toD3(Vec3 v) { return {v.x, v.y, v.z}; }
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 crossD(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dotD(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double lengthD(D3 a) { return std::sqrt(dotD(a, a)); }
bool finiteD(D3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
Vec3 toVec3(D3 a) { return {static_cast<float>(a.x), static_cast<float>(a.y), static_cast<float>(a.z)}; }

// Relative size below which a weighted sum counts as cancelled: its direction would be
// decided by rounding, not by the geometry.
constexpr double kCancelledFraction = 1e-6;

}  // namespace

std::size_t computeVertexNormals(std::span<const Vec3> positions, std::span<const std::uint32_t> indices,
                                 std::span<const std::uint8_t> recompute, std::vector<Vec3>* normals) {
  const std::size_t n = positions.size();
  normals->resize(n, kFallbackNormal);
  auto wanted = [&](std::size_t v) { return recompute.empty() || (v < recompute.size() && recompute[v] != 0); };

  std::vector<D3> sum(n);
  std::vector<double> weightSum(n, 0.0);
  std::vector<double> largestArea(n, -1.0);  // < 0: no usable triangle touches the vertex
  std::vector<D3> largestNormal(n);

  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t v[3] = {indices[t], indices[t + 1], indices[t + 2]};
    if (v[0] >= n || v[1] >= n || v[2] >= n) continue;
    if (!wanted(v[0]) && !wanted(v[1]) && !wanted(v[2])) continue;
    const D3 p[3] = {toD3(positions[v[0]]), toD3(positions[v[1]]), toD3(positions[v[2]])};
    if (!finiteD(p[0]) || !finiteD(p[1]) || !finiteD(p[2])) continue;
    const D3 c = crossD(sub(p[1], p[0]), sub(p[2], p[0]));
    const double twiceArea = lengthD(c);
    if (!(twiceArea > 0.0) || !std::isfinite(twiceArea)) continue;
    const D3 unit{c.x / twiceArea, c.y / twiceArea, c.z / twiceArea};
    const double area = 0.5 * twiceArea;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t vk = v[k];
      if (!wanted(vk)) continue;
      // Interior angle at corner k; |u × w| is twiceArea at every corner of the triangle.
      const D3 u = sub(p[(k + 1) % 3], p[k]);
      const D3 w = sub(p[(k + 2) % 3], p[k]);
      const double angle = std::atan2(twiceArea, dotD(u, w));
      const double weight = area * angle;
      sum[vk].x += unit.x * weight;
      sum[vk].y += unit.y * weight;
      sum[vk].z += unit.z * weight;
      weightSum[vk] += weight;
      if (area > largestArea[vk]) {
        largestArea[vk] = area;
        largestNormal[vk] = unit;
      }
    }
  }

  std::size_t fallbacks = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (!wanted(v)) continue;
    if (largestArea[v] < 0.0) {
      (*normals)[v] = kFallbackNormal;
      ++fallbacks;
      continue;
    }
    const double len = lengthD(sum[v]);
    if (!(len > kCancelledFraction * weightSum[v])) {
      (*normals)[v] = toVec3(largestNormal[v]);
      ++fallbacks;
      continue;
    }
    (*normals)[v] = toVec3({sum[v].x / len, sum[v].y / len, sum[v].z / len});
  }
  return fallbacks;
}

}  // namespace prt::bake
