#include "prt/octahedral_normal.h"

#include <algorithm>
#include <cmath>

namespace prt {
namespace {

constexpr float kScale = 32767.0f;

float signNotZero(float v) { return v >= 0.0f ? 1.0f : -1.0f; }

float snorm(std::int16_t c) { return std::max(static_cast<float>(c) / kScale, -1.0f); }

// Octahedral coordinates in [-1, 1]^2 of unit n: project onto |x|+|y|+|z| = 1, then fold the
// lower half over the diagonals.
std::array<float, 2> toOctahedron(Vec3 n) {
  const float inv = 1.0f / (std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z));
  float u = n.x * inv, v = n.y * inv;
  if (n.z < 0.0f) {
    const float fu = (1.0f - std::fabs(v)) * signNotZero(u), fv = (1.0f - std::fabs(u)) * signNotZero(v);
    u = fu;
    v = fv;
  }
  return {u, v};
}

std::int16_t clampCode(float c) { return static_cast<std::int16_t>(std::clamp(c, -kScale, kScale)); }

}  // namespace

Vec3 decodeOctahedralNormal(std::int16_t x, std::int16_t y) {
  const float u = snorm(x), v = snorm(y);
  Vec3 n{u, v, 1.0f - std::fabs(u) - std::fabs(v)};
  if (n.z < 0.0f) {
    n.x = (1.0f - std::fabs(v)) * signNotZero(u);
    n.y = (1.0f - std::fabs(u)) * signNotZero(v);
  }
  return n * (1.0f / length(n));  // |n| >= 1/sqrt(3) on the octahedron: never 0
}

std::array<std::int16_t, 2> encodeOctahedralNormal(Vec3 n) {
  const float len = length(n);
  if (!(len > 0.0f) || !std::isfinite(len)) return {0, 0};
  n = n * (1.0f / len);
  const std::array<float, 2> o = toOctahedron(n);
  const float fu = std::floor(o[0] * kScale), fv = std::floor(o[1] * kScale);
  std::array<std::int16_t, 2> best{clampCode(fu), clampCode(fv)};
  double bestDistance = 8.0;
  // Rounding each coordinate to nearest is not the closest decoding where the map stretches:
  // try all four corners of the code cell holding o. Closest by the squared distance in double:
  // a float dot product near 1 cannot tell angles of 1e-4 and 7e-3 degrees apart.
  for (int du = 0; du <= 1; ++du) {
    for (int dv = 0; dv <= 1; ++dv) {
      const std::array<std::int16_t, 2> c{clampCode(fu + static_cast<float>(du)), clampCode(fv + static_cast<float>(dv))};
      const Vec3 d = decodeOctahedralNormal(c[0], c[1]);
      const double ex = double{d.x} - n.x, ey = double{d.y} - n.y, ez = double{d.z} - n.z;
      const double distance = ex * ex + ey * ey + ez * ez;
      if (distance < bestDistance) {
        bestDistance = distance;
        best = c;
      }
    }
  }
  return best;
}

}  // namespace prt
