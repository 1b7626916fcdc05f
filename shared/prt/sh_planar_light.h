// SH of one-sided planar area lights seen from a point: a polygon or a disc of uniform
// radiance 1, projected from `point` through the exact spherical-polygon projection
// (prt/sh_polygon.h). A disc is a regular polygon of equal area (docs/analytic-lights.md
// gives the error against the edge count).
#pragma once

#include <span>

#include "prt/sh_polygon.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

// Edges of the polygon standing in for a disc by default: the largest coefficient error at
// order 8 is below 1e-4 of L_0 from points half a radius or more from the rim, 3.7e-3 at
// 0.1 radii (docs/analytic-lights.md, "Discs").
inline constexpr int kDefaultDiscEdges = 32;
inline constexpr int kMaxDiscEdges = 1024;

// Accumulates scale * the SH of the planar polygon `vertices` (world space, counter-clockwise
// seen from its emitting side) as seen from `point` into out[0 .. order^2) (double). The
// polygon must be simple. Errors: fewer than 3 or more than kMaxPolygonVertices vertices,
// non-finite values, zero area, vertices off one plane (by more than 1e-4 of its size), the
// point in the plane or behind it (the polygon emits toward its front only).
Status accumulatePlanarPolygon(const PolygonShProjector& projector, std::span<const Vec3> vertices, Vec3 point,
                               double scale, std::span<double> out);

// Same for a disc of `radius` > 0 about `centre`, emitting toward unit-or-not `normal`,
// replaced by an equal-area regular polygon of `edges` (3..kMaxDiscEdges) edges. Errors
// name the bad parameter, the point in the disc's plane or behind it.
Status accumulateDisc(const PolygonShProjector& projector, Vec3 centre, Vec3 normal, float radius, Vec3 point, int edges,
                      double scale, std::span<double> out);

}  // namespace prt
