// Sampling helpers shared by the brute-force references (direct_reference.cpp,
// glossy_reference.cpp), which deliberately share nothing with the bake's own sampling code
// (prt/sampling.h): a bug there must not hide in its reference. Private to baker/transfer.
#pragma once

#include <cmath>
#include <cstdint>

#include "prt/vec3.h"

namespace prt::bake::reference {

// Van der Corput radical inverse in base 2 of k, in [0, 1): the second Hammersley coordinate.
inline double radicalInverse2(std::uint32_t k) {
  std::uint32_t bits = k;
  bits = (bits << 16) | (bits >> 16);
  bits = ((bits & 0x55555555u) << 1) | ((bits & 0xAAAAAAAAu) >> 1);
  bits = ((bits & 0x33333333u) << 2) | ((bits & 0xCCCCCCCCu) >> 2);
  bits = ((bits & 0x0F0F0F0Fu) << 4) | ((bits & 0xF0F0F0F0u) >> 4);
  bits = ((bits & 0x00FF00FFu) << 8) | ((bits & 0xFF00FF00u) >> 8);
  return bits * (1.0 / 4294967296.0);
}

// Any two unit vectors completing `a` (unit) to an orthonormal frame (t1, t2, a).
inline void frameAround(Vec3 a, Vec3* t1, Vec3* t2) {
  const Vec3 helper = std::fabs(a.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 u = cross(helper, a);
  u = u * (1.0f / length(u));
  *t1 = u;
  *t2 = cross(a, u);
}

}  // namespace prt::bake::reference
