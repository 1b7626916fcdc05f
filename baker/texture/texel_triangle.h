// A triangle's UV footprint in texel units and the two geometric queries texel rasterisation
// needs: which texels of a row its interior reaches, and its point nearest a texel centre.
// Texel units: pixel = uv × size, so texel (x, y) covers [x, x+1) × [y, y+1) and its centre is
// (x + 0.5, y + 0.5); UV (0, 0) is the image's top-left corner (glTF).
#pragma once

#include <array>

namespace prt::bake {

struct TexelPoint {
  double x = 0, y = 0;
};

// Corners in texel units, in the order of the mesh's indices (either winding).
using TexelTriangle = std::array<TexelPoint, 3>;

// An inclusive range of texel columns or rows; empty when last < first.
struct TexelRange {
  int first = 0, last = -1;
};

// The rows whose open slab (y, y+1) meets the triangle's open interior, clamped to
// [0, height-1]; never empty (a sub-texel triangle gets its one row). Corners must be finite.
TexelRange texelRows(const TexelTriangle& t, int height);

// The texels of row y whose open squares meet the triangle's open interior (a positive-area
// overlap, so touching a square's edge or corner does not count), clamped to [0, width-1];
// never empty for a row of texelRows. Corners must be finite.
TexelRange texelRowSpan(const TexelTriangle& t, int y, int width);

// The point of the closed triangle nearest q.
struct NearestPoint {
  std::array<double, 3> bary{};  // weights of the corners, each >= 0, summing to 1
  double distance2 = 0;          // squared distance from q, texels²; 0 when q is inside or on an edge
};

// Nearest point of t to q, in t's texel units: q's own barycentrics when q is inside (or on the
// boundary), else the closest point of the nearest edge, so the result never leaves the
// triangle. t must not be degenerate (non-zero area).
NearestPoint nearestPoint(const TexelTriangle& t, TexelPoint q);

}  // namespace prt::bake
