// The real-SH triple-product tensor (Gaunt coefficients) C_ijk = integral over the sphere of
// y_i y_j y_k, in this project's basis (prt/sh_basis.h, docs/sh-conventions.md), for orders
// 1..8, stored sparsely; and the products built from it (docs/triple-product.md).
//
// Products are truncated: two order-n functions multiply into a function of order 2n-1, and
// everything here projects that product back onto the first n bands, exactly (no aliasing:
// the dropped bands are orthogonal to the kept ones).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "prt/status.h"

namespace prt {

inline constexpr int kMaxTripleProductOrder = 8;

// One non-zero coefficient. Indices are flat SH indices l(l+1)+m. Value in units of
// sr^(-1/2) (each orthonormal y_i carries sr^(-1/2); two of them integrate away).
struct ShTripleEntry {
  std::uint16_t i = 0, j = 0, k = 0;
  double value = 0.0;
};

// A view of the tensor of one order. Cheap to copy; the entries are owned by a process-wide
// table built on first use (a few ms, all orders at once, thread-safe initialisation) and
// never freed, so views stay valid for the whole program.
class ShTripleProduct {
 public:
  // The tensor of order `order` (n bands, n*n indices), 1 <= order <= kMaxTripleProductOrder;
  // otherwise an error naming the value. Safe on untrusted input.
  static Status make(int order, ShTripleProduct* out);

  int order() const { return order_; }

  // The non-zero coefficients with i <= j <= k, each once, sorted by k, then j, then i. Every
  // other non-zero is a permutation of one of these (C is fully symmetric). Because of the
  // sort, the order-n tensor is a prefix of the order-8 one.
  std::span<const ShTripleEntry> entries() const { return entries_; }

  // C_ijk for any index order; 0 for a zero coefficient and for an index outside
  // [0, order*order). Safe on any input.
  double at(int i, int j, int k) const;

  // Every non-zero as an ordered triple (all distinct permutations of each entry), sorted
  // by i, then j, then k: for each row-major product-matrix cell (i, j), its k run is
  // contiguous, the gather layout a shader forming P wants. Replaces *out.
  void expand(std::vector<ShTripleEntry>* out) const;

  // Product matrix P_ij = sum_k C_ijk L_k, so that (P t)_i is the order-n projection of the
  // product of the functions with coefficients L and t. `lighting` holds lightingOrder^2
  // coefficients (1 <= lightingOrder <= order; bands above lightingOrder count as zero);
  // `out` receives order^2 x order^2 floats, row-major (P is symmetric), and must hold at
  // least that many. Non-finite lighting is rejected. Safe on untrusted input.
  Status productMatrix(int lightingOrder, std::span<const float> lighting, std::span<float> out) const;

  // Fast path of productMatrix for trusted callers: same layout, no checks (debug asserts).
  // Float accumulation in entry order, so native and wasm results agree bit for bit.
  void productMatrixUnchecked(int lightingOrder, const float* lighting, float* out) const noexcept;

  // out = order-n projection of the product of the functions with coefficients a and b
  // (each order^2 floats used; sizes >= order^2). Double accumulation. out may alias a or b.
  // Non-finite inputs are rejected. Safe on untrusted input.
  Status multiply(std::span<const float> a, std::span<const float> b, std::span<float> out) const;

 private:
  int order_ = 0;
  std::span<const ShTripleEntry> entries_;
};

}  // namespace prt
