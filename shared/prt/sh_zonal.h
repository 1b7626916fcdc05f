// Analytic projections of circularly symmetric (zonal) functions (Lisle & Huang 2007 §3).
//
// A zonal function is stored by its band coefficients z_l: the coefficient of y_l0 when
// the symmetry axis is +z. Placing it on any axis n gives the full expansion
// c_lm = sqrt(4pi/(2l+1)) z_l y_lm(n) (addition theorem, Lisle & Huang Prop. 3.2).
#pragma once

#include <span>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

// Clamped cosine max(0, cos theta) about +z: z_l = pi H_l sqrt((2l+1)/4pi), with
// H_0 = 1, H_1 = 2/3, H_odd>1 = 0, H_{2n+2} = (1/2 - n)/(2 + n) H_{2n} (eq. 9-10).
// out.size() >= order. Lambertian exit radiance of albedo rho under lighting L_lm is
// (rho/pi) sum_lm L_lm c_lm where c is this function placed on the normal.
Status zonalClampedCosine(int order, std::span<float> out);

// H_l = 2 int_0^1 z P_l(z) dz for l = 0..order-1 (Lisle & Huang eq. 9). out.size() >= order.
Status clampedCosineH(int order, std::span<double> out);

// Circular light: radiance `radiance` inside a cap of angular radius zeta (radians,
// 0 < zeta <= pi) about +z, zero outside. z_l = 2pi (1 - cos zeta) f_l(cos zeta) y_l0(+z)
// with f_l from Lisle & Huang eq. 11. out.size() >= order.
Status zonalCircularLight(int order, float zeta, float radiance, std::span<float> out);

// Places zonal coefficients (z_0..z_{order-1}) on unit-or-not, non-zero `axis`:
// out[i] = sqrt(4pi/(2l+1)) z_l y_lm(axis). out.size() >= order*order.
Status placeZonal(int order, std::span<const float> zonal, Vec3 axis, std::span<float> out);

// Funk-Hecke convolution of `coeffs` with a zonal kernel: c'_lm = sqrt(4pi/(2l+1)) k_l c_lm.
// With k = zonalClampedCosine this turns radiance into irradiance. In place.
Status convolveZonal(int order, std::span<const float> kernel, std::span<float> coeffs);

}  // namespace prt
