// The glossy material model shared by baker, codec measurements and client
// (docs/glossy.md): a normalised Phong lobe about the mirror direction, its exact zonal SH
// coefficients, the glTF roughness mapping and Schlick's Fresnel term.
//
//   f(w) = (s+1)/(2pi) max(0, R.w)^s          (integrates to 1 over the sphere)
//   L_glossy = k_s * integral L_in(w) f(w) dw  (the cosine is part of the lobe, as in
//                                               Kautz et al. and Fujita & Kanai eq. 3)
// Funk-Hecke: the convolution scales band l of any SH function by
//   g_l(s) = alpha_l G*_l = (s+1) * integral_0^1 t^s P_l(t) dt,
// with I_0 = 1/(s+1), I_1 = 1/(s+2), I_l = (s-l+2)/(s+l+1) I_{l-2} (exact for real s >= 0).
#pragma once

#include <span>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

// Largest exponent the asset and the mapping produce by default: a mirror (roughness 0)
// becomes this lobe, whose g_l differ from 1 by about l(l+1)/(2s) < 1.2% for l <= 15.
inline constexpr double kDefaultMaxSpecularExponent = 10000.0;

// A vertex's specular reflectance: k_s = schlickFresnel(f0, n.v) times the lobe of exponent
// s. f0 in [0, 1] per channel (0.04 for glTF dielectrics, the base colour for metals; 0 for
// a purely diffuse surface), exponent finite and >= 0.
struct SpecularMaterial {
  Rgb f0;
  float exponent = 0.0f;
};

// g_l(s) for l = 0..order-1 into out[0..order) (out.size() >= order). s finite, >= 0.
// g_0 = 1 for every s; s = 0 is the uniform hemisphere about R, s = 1 the cosine lobe.
// Safe on untrusted input.
Status phongLobeBandScales(int order, double s, std::span<double> out);

// Unchecked float variant for trusted fast paths (order 1..16, s >= 0 finite): out[l] = g_l(s).
void phongLobeBandScalesUnchecked(int order, float s, float* out) noexcept;

// glTF perceptual roughness r in [0, 1] -> Phong exponent about the mirror direction:
// alpha = r^2, Blinn-Phong exponent 2/alpha^2 - 2 (Walter et al. 2007's Beckmann match),
// divided by 4 because (n.h)^e ~ (R.w)^(e/4) for small angles; capped at maxExponent
// (roughness 0 would be a perfect mirror, s = infinity). r outside [0,1] is an error.
Status specularExponentFromRoughness(double roughness, double maxExponent, double* exponent);

// Schlick: F = F0 + (1 - F0)(1 - cos)^5 with cos = n.v clamped to [0, 1] (a vertex seen
// from behind its tangent plane takes the grazing value 1).
Rgb schlickFresnel(Rgb f0, float cosNormalView) noexcept;

// Mirror direction of the unit view vector v (surface to eye) about unit normal n:
// R = 2 (n.v) n - v.
Vec3 reflectView(Vec3 toEye, Vec3 normal) noexcept;

}  // namespace prt
