// Bi-scale exit radiance (Sloan et al. 2003, eq. 4; docs/bi-scale.md): a radiance transfer
// texture looked up at a point's patch position and view, dotted with the point's macro-scale
// transferred radiance rotated into its tangent frame. The CPU reference of the bi-scale
// path (tests, prt-bake shade, the client's checks).
#pragma once

#include <span>

#include "prt/rtt.h"
#include "prt/status.h"
#include "prt/transfer_matrix.h"
#include "prt/vec3.h"

namespace prt {

// A point's tangent frame: unit tangent (the patch's +x, along u), unit normal (+z); the
// bitangent (+y, along v) is cross(normal, tangent), so the frame is right-handed.
struct TangentFrame {
  Vec3 tangent{1, 0, 0};
  Vec3 normal{0, 0, 1};
};

// B at patch position (u, v) (taken modulo 1) toward `view` (unit, tangent frame): the nearest
// spatial sample, bilinear across the four nearest view samples (clamped to the view square;
// a view below the horizon is taken at it). `viewDependent` false reads the centre view only
// (the paper's Figure 6c: view-dependence switched off). out: channels * order^2 floats.
void rttLookup(const Rtt& rtt, float u, float v, Vec3 view, bool viewDependent, float* out);

// Per point p: T_c = M_c L_c (world frame; `matrices` [point][channel][packed entry] of
// order-`order` matrices in `packing`, channels 1 or 3), rotated into p's frame by the SH
// rotation of its world-to-tangent rotation, dotted with B(q_p, w_p) (w_p the direction to
// `eye` in p's frame; an RGB RTT per channel, a grey one for all three):
//   out[3p + c] = sum_i B_c,i(q_p, w_p) (D_p M_c L_c)_i,   i < b^2,
// b = min(order, rtt.order, bands of `lighting`). `patchUv`: 2 floats a point (q_p). A point
// at the eye gets 0. kInvalidArgument or kSizeMismatch for inconsistent sizes or a frame that
// is not orthonormal. Safe on untrusted sizes.
Status biScaleExitRadiance(const Rtt& rtt, std::span<const float> matrices, int order, MatrixPacking packing, int channels,
                           std::span<const Vec3> positions, std::span<const TangentFrame> frames, std::span<const float> patchUv,
                           Vec3 eye, bool viewDependent, std::span<const Rgb> lighting, std::span<float> out);

}  // namespace prt
