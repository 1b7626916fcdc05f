// Patch placements of a synthesised id map (docs/bi-scale.md, "Synthesised id map"): where
// the radiance transfer texture's periodic patch lies on the surface around one seed. A point
// p of the seed's cell reads the RTT at q(p), its position in the patch, in patch widths from
// the placement's origin along its axes. Shared: the baker synthesises placements, the client
// evaluates q per fragment, and both must agree to the bit.
#pragma once

#include <cstddef>
#include <cstdint>

#include "prt/vec3.h"

namespace prt {

// origin: world space; axisU, axisV: orthogonal, in the seed's tangent plane, each of length
// 1 / patchWidth, so a dot product with them counts patch widths. axisU is patchTangent(n),
// axisV is cross(n, axisU) (the right-handed TangentFrame of prt/bi_scale.h), both scaled.
struct PatchPlacement {
  Vec3 origin;
  Vec3 axisU;
  Vec3 axisV;
};

// An id map texel no surface reaches; placement indices are 0 … kMaxPatchPlacements - 1.
inline constexpr std::uint16_t kNoPlacement = 0xFFFF;
inline constexpr std::size_t kMaxPatchPlacements = 65535;

// Below this length of +x projected onto the tangent plane, patchTangent projects +z instead.
inline constexpr float kPatchTangentFallback = 0.3f;

// q(p) = (fract(dot(p - origin, axisU)), fract(dot(p - origin, axisV))), each in [0, 1):
// p's position in the patch. Float arithmetic in this order (the client's shader repeats
// it). A non-finite result (NaN or infinite input) gives 0. Safe on untrusted input.
void patchCoordinates(const PatchPlacement& placement, Vec3 p, float* u, float* v);

// The patch's u direction at a surface point of normal `normal` (any non-zero length): unit,
// orthogonal to the normal, the projection of world +x onto the tangent plane, or of +z where
// that projection is shorter than kPatchTangentFallback (within 17.5° of ±x). One global
// field, so the pattern's threads run the same way across cells and the vertices' tangent
// frames agree with the placements; it is smooth except on the two circles where it switches
// (the hairy-ball theorem forbids a field smooth everywhere on a sphere). A zero or
// non-finite normal gives (1, 0, 0). Safe on untrusted input; deterministic.
Vec3 patchTangent(Vec3 normal);

}  // namespace prt
