#include "mesh_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prt::serve {
namespace {

// Twice the signed area of (a, b, p): positive when p is to the right of a->b with y down
// (clockwise on screen).
double edge(double ax, double ay, double bx, double by, double px, double py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// The top-left rule for an edge a->b of a triangle whose area is positive (clockwise on a
// y-down screen): a top edge is horizontal with the interior below; a left edge goes up.
bool topLeft(double ax, double ay, double bx, double by) {
  return (ay == by && bx > ax) || by < ay;
}

bool usable(const RasterVertex& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.depth) && v.depth > 0.0f &&
         std::isfinite(v.colour.r) && std::isfinite(v.colour.g) && std::isfinite(v.colour.b);
}

}  // namespace

RasterTarget::RasterTarget(int w, int h)
    : width(w),
      height(h),
      colour(static_cast<std::size_t>(w) * h),
      depth(static_cast<std::size_t>(w) * h, std::numeric_limits<float>::infinity()),
      covered(static_cast<std::size_t>(w) * h, 0) {}

void drawTriangle(RasterTarget& target, const RasterVertex& a0, const RasterVertex& b0, const RasterVertex& c0) {
  if (!usable(a0) || !usable(b0) || !usable(c0)) return;
  // Orient clockwise on screen (positive area), so one inside test and one fill rule serve both windings.
  const RasterVertex* v[3] = {&a0, &b0, &c0};
  double area = edge(a0.x, a0.y, b0.x, b0.y, c0.x, c0.y);
  if (area < 0.0) {
    std::swap(v[1], v[2]);
    area = -area;
  }
  if (!(area > 0.0)) return;
  const RasterVertex &a = *v[0], &b = *v[1], &c = *v[2];
  const double minX = std::min({a.x, b.x, c.x}), maxX = std::max({a.x, b.x, c.x});
  const double minY = std::min({a.y, b.y, c.y}), maxY = std::max({a.y, b.y, c.y});
  // Pixels whose centre (i + 0.5) can lie in [min, max], clipped to the target in double
  // first: a float far outside int's range must not reach the conversion.
  const auto pixelRange = [](double lo, double hi, int size, int* first, int* last) {
    *first = static_cast<int>(std::clamp(std::ceil(lo - 0.5), 0.0, static_cast<double>(size)));
    *last = static_cast<int>(std::clamp(std::floor(hi - 0.5), -1.0, static_cast<double>(size - 1)));
  };
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  pixelRange(minX, maxX, target.width, &x0, &x1);
  pixelRange(minY, maxY, target.height, &y0, &y1);
  if (x0 > x1 || y0 > y1) return;
  // Edge i is opposite vertex i; its function is that vertex's barycentric weight x area.
  const bool tl0 = topLeft(b.x, b.y, c.x, c.y), tl1 = topLeft(c.x, c.y, a.x, a.y), tl2 = topLeft(a.x, a.y, b.x, b.y);
  const double invA = 1.0 / a.depth, invB = 1.0 / b.depth, invC = 1.0 / c.depth;
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5;
      const double w0 = edge(b.x, b.y, c.x, c.y, px, py);
      const double w1 = edge(c.x, c.y, a.x, a.y, px, py);
      const double w2 = edge(a.x, a.y, b.x, b.y, px, py);
      if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
      if ((w0 == 0.0 && !tl0) || (w1 == 0.0 && !tl1) || (w2 == 0.0 && !tl2)) continue;
      const double l0 = w0 / area, l1 = w1 / area, l2 = w2 / area;
      const float depth = static_cast<float>(1.0 / (l0 * invA + l1 * invB + l2 * invC));
      const std::size_t i = static_cast<std::size_t>(y) * target.width + x;
      if (!(depth < target.depth[i])) continue;
      target.depth[i] = depth;
      target.covered[i] = 1;
      target.colour[i] = {static_cast<float>(l0 * a.colour.r + l1 * b.colour.r + l2 * c.colour.r),
                          static_cast<float>(l0 * a.colour.g + l1 * b.colour.g + l2 * c.colour.g),
                          static_cast<float>(l0 * a.colour.b + l1 * b.colour.b + l2 * c.colour.b)};
    }
  }
}

}  // namespace prt::serve
