// The real-SH triple-product tensor (Gaunt coefficients) C_ijk = integral over the sphere of
// y_i y_j y_k, in this project's basis (prt/sh_basis.h, docs/sh-conventions.md), for orders
// 1..8, stored sparsely; and the products built from it (docs/triple-product.md).
//
// Products are truncated: two order-n functions multiply into a function of order 2n-1, and
// everything here projects that product back onto the first n bands, exactly (no aliasing:
// the dropped bands are orthogonal to the kept ones). The second factor may have up to
// 2n-1 bands (transferOrder), which makes the order-n projection of the product with an
// unlimited function exact (the bands above 2n-2 do not reach the first n).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "prt/status.h"

namespace prt {

inline constexpr int kMaxTripleProductOrder = 8;
// A product of two order-8 functions has 2*8-1 = 15 bands; a transfer of that order makes the
// product matrix exact (docs/triple-product.md, "Orders, truncation and the transfer order").
inline constexpr int kMaxTripleTransferOrder = 2 * kMaxTripleProductOrder - 1;

// One non-zero coefficient. Indices are flat SH indices l(l+1)+m. Value in units of
// sr^(-1/2) (each orthonormal y_i carries sr^(-1/2); two of them integrate away).
struct ShTripleEntry {
  std::uint16_t i = 0, j = 0, k = 0;
  double value = 0.0;
};

// The tensor restricted to i, j < order^2 (output and lighting) and k < transferOrder^2
// (the function the lighting multiplies, e.g. a texel's visibility). Values come from a
// process-wide table built on first use (tens of ms, thread-safe initialisation); each object
// owns a copy of its part (at most 128 KiB), so it is self-contained.
class ShTripleProduct {
 public:
  // 1 <= order <= kMaxTripleProductOrder and order <= transferOrder <= 2*order-1; otherwise
  // an error naming the value. Safe on untrusted input.
  static Status make(int order, int transferOrder, ShTripleProduct* out);
  // The square tensor: transferOrder = order.
  static Status make(int order, ShTripleProduct* out) { return make(order, order, out); }

  int order() const { return order_; }
  int transferOrder() const { return transferOrder_; }

  // The non-zero coefficients, each unordered index triple once, as i <= j <= k (so i, j <
  // order^2 and k < transferOrder^2), sorted by k, then j, then i. C is fully symmetric: every
  // other non-zero of the restricted tensor is a permutation of one of these that keeps the
  // first two indices below order^2.
  std::span<const ShTripleEntry> entries() const { return entries_; }

  // C_ijk for any index order when the sorted triple is stored (two smaller indices below
  // order^2, the largest below transferOrder^2), else 0. Symmetric in its arguments. Safe on
  // any input.
  double at(int i, int j, int k) const;

  // Every non-zero (i, j, k) with i, j < order^2 and k < transferOrder^2 as an ordered triple,
  // sorted by i, then k, then j: the j run of each product-matrix cell (i, k) is contiguous,
  // the gather layout a shader forming P wants. Replaces *out.
  void expand(std::vector<ShTripleEntry>* out) const;

  // Product matrix P_ik = sum_j C_ijk L_j, so that (P t)_i is the order-n projection of the
  // product of the lighting (coefficients L) and the function with coefficients t (order
  // transferOrder). `lighting` holds lightingOrder^2 coefficients (1 <= lightingOrder <=
  // order; bands above lightingOrder count as zero); `out` receives order^2 rows of
  // transferOrder^2 floats, row-major, and must hold at least that many (symmetric when
  // transferOrder = order). Non-finite lighting is rejected. Safe on untrusted input.
  Status productMatrix(int lightingOrder, std::span<const float> lighting, std::span<float> out) const;

  // Fast path of productMatrix for trusted callers: same layout, no checks (debug asserts).
  // Float accumulation in entry order, so native and wasm results agree bit for bit.
  void productMatrixUnchecked(int lightingOrder, const float* lighting, float* out) const noexcept;

  // out = order-n projection of the product of a (order^2 floats used) and b
  // (transferOrder^2 floats used); out holds order^2. Double accumulation. out may alias a
  // or b. Non-finite inputs are rejected. Safe on untrusted input.
  Status multiply(std::span<const float> a, std::span<const float> b, std::span<float> out) const;

 private:
  // Calls f(i, j, k, value) for each ordered non-zero of the restricted tensor.
  template <typename F>
  void forEachOrdered(F&& f) const;

  int order_ = 0, transferOrder_ = 0;
  std::vector<ShTripleEntry> entries_;
};

}  // namespace prt
