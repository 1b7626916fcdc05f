// Real spherical-harmonic basis evaluation (Lisle & Huang 2007 algebraic recurrence).
//
// Conventions (docs/sh-conventions.md): real SH, flat index i = l(l+1)+m, z is the polar
// axis, no Condon-Shortley phase: y(1,-1) = +0.488603 y, y(1,0) = +0.488603 z,
// y(1,1) = +0.488603 x. "Order n" means n bands (l = 0..n-1) and n*n coefficients.
#pragma once

#include <cstddef>
#include <span>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

inline constexpr int kMinShOrder = 1;
inline constexpr int kMaxShOrder = 16;  // l <= 15: 12 were asked for, more costs nothing

// Number of coefficients of an order-n expansion (n bands): n*n.
constexpr int shCoeffCount(int order) { return order * order; }
// Flat index of (l, m), -l <= m <= l.
constexpr int shIndex(int l, int m) { return l * (l + 1) + m; }
// Band l of flat index i.
int shBandOf(int index);

// Ok when kMinShOrder <= order <= kMaxShOrder; otherwise an error naming the value.
Status checkShOrder(int order);

// Writes the order*order basis values y_i(dir) into out[0 .. order*order).
// Checked entry point: order in [1, kMaxShOrder], dir finite and non-zero (it is normalised here),
// out.size() >= order*order. Safe on untrusted input.
Status evalShBasis(int order, Vec3 dir, std::span<float> out);

// Fast path for trusted callers: dir must be unit length, order in [1, kMaxShOrder], out holds
// order*order floats. No checks.
void evalShBasisUnchecked(int order, Vec3 dir, float* out) noexcept;

// Batched evaluation of `count` unit directions given as separate x, y, z arrays.
// Output is coefficient-major: out[i * count + k] = y_i(dir_k), so consumers can run
// vectorised loops over directions for each coefficient.
// Checks: order range, array sizes (x, y, z >= count, out >= order*order*count), and that
// every direction is finite with |len^2 - 1| <= 1e-3 (directions are not renormalised).
Status evalShBasisBatch(int order, std::span<const float> x, std::span<const float> y,
                        std::span<const float> z, std::span<float> out);

// Unchecked batched evaluation (same layout); inputs must satisfy the checks above.
void evalShBasisBatchUnchecked(int order, std::size_t count, const float* x, const float* y,
                               const float* z, float* out) noexcept;

}  // namespace prt
