#include "baker/scene/mesh_tangents.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace prt::bake {
namespace {

struct D3 {
  double x = 0, y = 0, z = 0;
};
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 toD(Vec3 v) { return {v.x, v.y, v.z}; }
bool finite(D3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Interior angle at corner a of triangle (a, b, c).
double cornerAngle(D3 a, D3 b, D3 c) {
  const D3 e1 = b - a, e2 = c - a;
  return std::atan2(std::sqrt(dot(cross(e1, e2), cross(e1, e2))), dot(e1, e2));
}

}  // namespace

Vec3 anyOrthogonal(Vec3 n) {
  // Cross with the axis least aligned with n: never near-parallel, so never degenerate.
  const float ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  const Vec3 axis = ax <= ay && ax <= az ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
  const Vec3 t = cross(n, axis);
  return t * (1.0f / length(t));
}

std::size_t computeVertexTangents(std::span<const Vec3> positions, std::span<const Vec3> normals,
                                  std::span<const Uv> uvs, std::span<const std::uint32_t> indices,
                                  std::span<const std::uint8_t> recompute, std::vector<Tangent>* tangents) {
  const std::size_t n = positions.size();
  tangents->resize(n);
  if (normals.size() != n || uvs.size() != n || recompute.size() != n) return 0;
  std::vector<D3> sumT(n), sumB(n);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::array<std::uint32_t, 3> v{indices[t], indices[t + 1], indices[t + 2]};
    if (v[0] >= n || v[1] >= n || v[2] >= n) continue;
    if (!recompute[v[0]] && !recompute[v[1]] && !recompute[v[2]]) continue;
    const D3 p0 = toD(positions[v[0]]), p1 = toD(positions[v[1]]), p2 = toD(positions[v[2]]);
    const D3 e1 = p1 - p0, e2 = p2 - p0;
    const double du1 = double{uvs[v[1]].u} - uvs[v[0]].u, dv1 = double{uvs[v[1]].v} - uvs[v[0]].v;
    const double du2 = double{uvs[v[2]].u} - uvs[v[0]].u, dv2 = double{uvs[v[2]].v} - uvs[v[0]].v;
    const double det = du1 * dv2 - du2 * dv1;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) continue;
    // dp/du and dp/dv of the affine map from uv to the triangle's plane.
    const D3 dpdu = (e1 * dv2 - e2 * dv1) * (1.0 / det);
    const D3 dpdv = (e2 * du1 - e1 * du2) * (1.0 / det);
    if (!finite(dpdu) || !finite(dpdv)) continue;
    // Unit directions so a stretched chart does not outweigh its neighbours; -dp/dv is "up".
    const double lu = std::sqrt(dot(dpdu, dpdu)), lv = std::sqrt(dot(dpdv, dpdv));
    if (!(lu > 0.0) || !(lv > 0.0)) continue;
    const D3 tu = dpdu * (1.0 / lu), bu = dpdv * (-1.0 / lv);
    const std::array<double, 3> angle{cornerAngle(p0, p1, p2), cornerAngle(p1, p2, p0), cornerAngle(p2, p0, p1)};
    for (int k = 0; k < 3; ++k) {
      if (!recompute[v[k]] || !std::isfinite(angle[k])) continue;
      sumT[v[k]] = sumT[v[k]] + tu * angle[k];
      sumB[v[k]] = sumB[v[k]] + bu * angle[k];
    }
  }
  std::size_t fallbacks = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (!recompute[v]) continue;
    const D3 nv = toD(normals[v]);
    D3 t = sumT[v] - nv * dot(nv, sumT[v]);
    const double len = std::sqrt(dot(t, t));
    if (!(len > 1e-12) || !std::isfinite(len)) {
      (*tangents)[v] = {anyOrthogonal(normals[v]), 1.0f};
      ++fallbacks;
      continue;
    }
    t = t * (1.0 / len);
    const float handedness = dot(cross(nv, t), sumB[v]) < 0.0 ? -1.0f : 1.0f;
    (*tangents)[v] = {Vec3{static_cast<float>(t.x), static_cast<float>(t.y), static_cast<float>(t.z)}, handedness};
  }
  return fallbacks;
}

}  // namespace prt::bake
