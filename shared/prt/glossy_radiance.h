// Glossy exit radiance of per-vertex transfer matrices under SH lighting: the one CPU
// reference every consumer uses (prt-bake shade, compress-report, the wasm core, the CPU
// emulation of the glossy shaders, the tests). docs/glossy.md has the derivation.
//
// For vertex x (position p, unit normal n, material f0, s), eye e and channel c:
//   v = (e - p)/|e - p|,  R = 2(n.v)n - v,  k_s = f0 + (f90 - f0)(1 - max(0, n.v))^5
//   L_c = k_s,c * sum_i g_l(i)(s) (M_c L_c)_i y_i(R)
// with M_c the channel's transfer matrix (one shared matrix for 1-channel passes), L_c the
// lighting's channel c, g_l the Phong lobe's band scales (prt/glossy_lobe.h) and i over
// the first bands^2 coefficients.
#pragma once

#include <cstddef>
#include <span>

#include "prt/glossy_lobe.h"
#include "prt/sh_triple_product.h"
#include "prt/status.h"
#include "prt/transfer_matrix.h"
#include "prt/vec3.h"

namespace prt {

struct GlossyView {
  Vec3 eye{};                 // world space
  bool includeFresnel = true; // false: k_s = f0 (tests of the lobe alone)
};

// `matrices`: [vertex][channel][packed entry] of order-`order` matrices in `packing`,
// channels 1 or 3. lighting.size() = bands^2 with 1 <= bands <= order. positions, normals and
// specular one per vertex; out 3 per vertex ([vertex][rgb]). A vertex at the eye (v undefined)
// gets 0. Float accumulation. Safe on untrusted sizes.
Status glossyExitRadiance(std::span<const float> matrices, int order, MatrixPacking packing, int channels,
                          std::span<const Vec3> positions, std::span<const Vec3> normals,
                          std::span<const SpecularMaterial> specular, const GlossyView& view,
                          std::span<const Rgb> lighting, std::span<float> out);

// The same with double accumulation: the reference codec and bake errors are measured against.
Status glossyExitRadianceDouble(std::span<const float> matrices, int order, MatrixPacking packing, int channels,
                                std::span<const Vec3> positions, std::span<const Vec3> normals,
                                std::span<const SpecularMaterial> specular, const GlossyView& view,
                                std::span<const Rgb> lighting, std::span<double> out);

// The same exit radiance by the triple product with fixed lighting (TPFL; PRTT §3, Sloan
// 2008; docs/transfer-textures.md, "Glossy by the triple product"): each point stores a
// visibility vector V ([point][m^2], m = product.transferOrder(), one channel, no albedo), the
// frame forms P_c = sum_j C_ijk L_c,j once (product.productMatrix; n = product.order() bands
// of lighting, lighting.size() = n^2), and P_c V takes the place of M_c L_c above. With
// m = 2n - 1 this equals the matrix form for the matrix M_ij = integral V y_i y_j of the same
// visibility to rounding. positions, normals, specular one per point; out 3 per point. Float
// accumulation. Safe on untrusted sizes.
Status tpflGlossyExitRadiance(const ShTripleProduct& product, std::span<const float> visibility,
                              std::span<const Vec3> positions, std::span<const Vec3> normals,
                              std::span<const SpecularMaterial> specular, const GlossyView& view,
                              std::span<const Rgb> lighting, std::span<float> out);

}  // namespace prt
