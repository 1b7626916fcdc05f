// Exact SH projection of a uniform spherical polygon (Wang & Ramamoorthi 2018, "Analytic
// spherical harmonic coefficients for polygonal area lights", TOG 37(4)): each band l is
// written as 2l+1 zonal lobes P_l(w_j . u) in fixed directions w_j, and the integral of a
// zonal lobe over the polygon is a sum over its edges of closed-form arc integrals (a
// boundary integral from P_l being an eigenfunction of the spherical Laplacian).
// Derivation, conventions and accuracy: docs/analytic-lights.md.
#pragma once

#include <span>
#include <vector>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

inline constexpr int kMaxPolygonShOrder = 8;
inline constexpr int kMaxPolygonVertices = 4096;

class PolygonShProjector {
 public:
  // Precomputes the lobe directions and the per-band lobe-to-SH matrices for orders
  // 1..kMaxPolygonShOrder; other orders give an error naming the value.
  static Status make(int order, PolygonShProjector* out);

  int order() const { return order_; }

  // Coefficients of the indicator of the spherical polygon with vertex directions
  // `vertices` (any non-zero length; normalised here), joined by the shorter great arcs and
  // counter-clockwise seen from outside the sphere (interior on the left). Any simple
  // polygon: concave, or covering more than a hemisphere. out.size() >= order^2. Errors:
  // fewer than 3 or more than kMaxPolygonVertices vertices, non-finite or zero vertices,
  // consecutive vertices coinciding or antipodal, an edge doubling back (no interior there).
  // Vertices all on one great circle, going round once, bound a hemisphere.
  Status projectSpherical(std::span<const Vec3> vertices, std::span<float> out) const;

  // The same without checks, for callers that validated the polygon (the planar and disc
  // projections): `unitVertices` are unit length and the polygon passes the checks above.
  // Accumulates scale * coefficients into out[0 .. order^2) (double, so sums of many lights
  // stay exact to float).
  void accumulateUnchecked(std::span<const double> unitVertices, double scale, double* out) const;

 private:
  int order_ = 0;
  int lobeCount_ = 0;               // 2 order - 1, shared by all bands
  std::vector<double> lobes_;       // x, y, z per lobe
  std::vector<double> lobeToSh_;    // band l: (2l+1) x (2l+1), row m, column lobe j
  std::vector<double> dLegendre_;   // P_l'(x) = sum_k dLegendre_[l * order + k] x^k
};

}  // namespace prt
