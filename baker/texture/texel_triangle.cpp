#include "baker/texture/texel_triangle.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prt::bake {
namespace {

// Twice the signed area of (a, b, c): positive when counter-clockwise in a y-up frame.
double orient(TexelPoint a, TexelPoint b, TexelPoint c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Clamped in floating point before the conversion, so no value can overflow int.
int clampedIndex(double v, int last) { return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(last))); }

}  // namespace

TexelRange texelRows(const TexelTriangle& t, int height) {
  const double minY = std::min({t[0].y, t[1].y, t[2].y});
  const double maxY = std::max({t[0].y, t[1].y, t[2].y});
  // Row y's open slab meets the open interval (minY, maxY) iff minY < y + 1 and y < maxY.
  TexelRange r{clampedIndex(std::floor(minY), height - 1), clampedIndex(std::ceil(maxY) - 1.0, height - 1)};
  r.last = std::max(r.last, r.first);
  return r;
}

TexelRange texelRowSpan(const TexelTriangle& t, int y, int width) {
  // The x-extent of the triangle clipped to the closed slab [y, y+1]: its corners inside the
  // slab and its edges' crossings of the slab's two lines. Because the clipped polygon is
  // convex with a non-empty interior, texel x's open square meets it iff x < hi and x + 1 > lo.
  const double y0 = y, y1 = y + 1.0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  auto include = [&](double x) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  };
  for (int i = 0; i < 3; ++i) {
    if (t[i].y >= y0 && t[i].y <= y1) include(t[i].x);
  }
  for (int i = 0; i < 3; ++i) {
    const TexelPoint a = t[i], b = t[(i + 1) % 3];
    const double ya = std::min(a.y, b.y), yb = std::max(a.y, b.y);
    for (double c : {y0, y1}) {
      if (!(c > ya && c < yb)) continue;  // also skips horizontal edges
      const double x = a.x + (c - a.y) * (b.x - a.x) / (b.y - a.y);
      // Rounding must not push the crossing past the edge's own extent.
      include(std::clamp(x, std::min(a.x, b.x), std::max(a.x, b.x)));
    }
  }
  if (lo > hi) return {};
  TexelRange r{clampedIndex(std::floor(lo), width - 1), clampedIndex(std::ceil(hi) - 1.0, width - 1)};
  // A sliver thinner than rounding (lo == hi on a texel line) still has area: keep its texel.
  r.last = std::max(r.last, r.first);
  return r;
}

NearestPoint nearestPoint(const TexelTriangle& t, TexelPoint q) {
  const double area = orient(t[0], t[1], t[2]);
  const std::array<double, 3> l{orient(q, t[1], t[2]) / area, orient(t[0], q, t[2]) / area,
                                orient(t[0], t[1], q) / area};
  NearestPoint out;
  if (l[0] >= 0.0 && l[1] >= 0.0 && l[2] >= 0.0) {
    const double sum = l[0] + l[1] + l[2];
    out.bary = {l[0] / sum, l[1] / sum, l[2] / sum};
    return out;
  }
  // Outside: the nearest point of a convex polygon to an outside point is on its boundary.
  out.distance2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const TexelPoint a = t[i], b = t[j];
    const double ex = b.x - a.x, ey = b.y - a.y;
    const double len2 = ex * ex + ey * ey;
    const double s = len2 > 0.0 ? std::clamp(((q.x - a.x) * ex + (q.y - a.y) * ey) / len2, 0.0, 1.0) : 0.0;
    const double dx = a.x + s * ex - q.x, dy = a.y + s * ey - q.y;
    const double d2 = dx * dx + dy * dy;
    if (d2 < out.distance2) {
      out.distance2 = d2;
      out.bary = {0.0, 0.0, 0.0};
      out.bary[static_cast<std::size_t>(i)] = 1.0 - s;
      out.bary[static_cast<std::size_t>(j)] = s;
    }
  }
  return out;
}

}  // namespace prt::bake
