#include "prt/sh_triple_product.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <complex>
#include <string>

#include "prt/sh_basis.h"
#include "prt/wigner3j.h"

namespace prt {
namespace {

using Complex = std::complex<double>;

// Our real y_lm as a combination of complex Y_l^mu with the Condon-Shortley phase (the phase
// of complexGaunt). Dropping the phase in the real basis cancels the (-1)^m that the usual
// real-from-complex formulas carry, giving exactly sqrt2 K P cos(m phi) and sqrt2 K P sin:
//   m > 0: y_lm    = (Y_l^-m + (-1)^m Y_l^m) / sqrt2
//   m = 0: y_l0    = Y_l^0
//   m < 0: y_l,-a  = i (Y_l^-a - (-1)^a Y_l^a) / sqrt2,  a = |m|
struct RealFromComplex {
  int count = 0;
  int mu[2] = {0, 0};
  Complex coeff[2];
};

RealFromComplex realFromComplex(int m) {
  RealFromComplex r;
  if (m == 0) {
    r.count = 1;
    r.coeff[0] = 1.0;
    return r;
  }
  const double s = 1.0 / std::sqrt(2.0);
  const int a = m < 0 ? -m : m;
  const double phase = a % 2 == 0 ? 1.0 : -1.0;
  r.count = 2;
  r.mu[0] = -a;
  r.mu[1] = a;
  if (m > 0) {
    r.coeff[0] = s;
    r.coeff[1] = phase * s;
  } else {
    r.coeff[0] = Complex(0.0, s);
    r.coeff[1] = Complex(0.0, -phase * s);
  }
  return r;
}

// Real Gaunt coefficient by the unitary change of basis applied to the complex Gaunt
// coefficients: exact up to double rounding (the Racah sums are finite and closed form).
double realGaunt(int l1, int m1, int l2, int m2, int l3, int m3) {
  if ((l1 + l2 + l3) % 2 != 0) return 0.0;
  if (l3 > l1 + l2 || l3 < std::abs(l1 - l2)) return 0.0;
  const RealFromComplex u1 = realFromComplex(m1), u2 = realFromComplex(m2), u3 = realFromComplex(m3);
  Complex sum = 0.0;
  for (int a = 0; a < u1.count; ++a) {
    for (int b = 0; b < u2.count; ++b) {
      for (int c = 0; c < u3.count; ++c) {
        if (u1.mu[a] + u2.mu[b] + u3.mu[c] != 0) continue;
        sum += u1.coeff[a] * u2.coeff[b] * u3.coeff[c] * complexGaunt(l1, l2, l3, u1.mu[a], u2.mu[b], u3.mu[c]);
      }
    }
  }
  // The combination of a real integrand is real; an imaginary part would mean a wrong phase.
  assert(std::fabs(sum.imag()) < 1e-12);
  return sum.real();
}

// Below this a computed coefficient is a rounding residue of an exact zero: true non-zeros
// (l <= 7 for two indices, <= 14 for the third) are above 6e-5 in magnitude, exact zeros come
// out below 1e-15.
constexpr double kZero = 1e-12;

// Every non-zero any (order, transferOrder) view needs: i <= j <= k with j < 8^2 and k < 15^2,
// sorted by (k, j, i).
struct Table {
  std::vector<ShTripleEntry> entries;

  Table() {
    const int pairCount = shCoeffCount(kMaxTripleProductOrder);
    const int count = shCoeffCount(kMaxTripleTransferOrder);
    std::vector<int> band(count);
    for (int i = 0; i < count; ++i) band[i] = shBandOf(i);
    for (int k = 0; k < count; ++k) {
      const int lk = band[k], mk = k - lk * (lk + 1);
      for (int j = 0; j <= k && j < pairCount; ++j) {
        const int lj = band[j], mj = j - lj * (lj + 1);
        for (int i = 0; i <= j; ++i) {
          const int li = band[i], mi = i - li * (li + 1);
          const double v = realGaunt(li, mi, lj, mj, lk, mk);
          if (std::fabs(v) > kZero) {
            entries.push_back({static_cast<std::uint16_t>(i), static_cast<std::uint16_t>(j),
                               static_cast<std::uint16_t>(k), v});
          }
        }
      }
    }
  }
};

const Table& table() {
  static const Table t;
  return t;
}

// Calls f(p, q, r) once for each distinct ordering of a canonical entry's indices.
template <typename F>
void forEachPermutation(const ShTripleEntry& e, F&& f) {
  const int a = e.i, b = e.j, c = e.k;
  if (a == c) {
    f(a, a, a);
  } else if (a == b) {
    f(a, a, c), f(a, c, a), f(c, a, a);
  } else if (b == c) {
    f(a, b, b), f(b, a, b), f(b, b, a);
  } else {
    f(a, b, c), f(a, c, b), f(b, a, c), f(b, c, a), f(c, a, b), f(c, b, a);
  }
}

Status checkFinite(std::span<const float> v, std::size_t n, const char* what) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) {
      return Status::error(StatusCode::kNotFinite, std::string(what) + " coefficient " + std::to_string(i) +
                                                       " is not finite");
    }
  }
  return Status::ok();
}

Status checkSize(std::span<const float> v, std::size_t n, const char* what) {
  if (v.size() < n) {
    return Status::error(StatusCode::kSizeMismatch, std::string(what) + " holds " + std::to_string(v.size()) +
                                                        " floats, " + std::to_string(n) + " needed");
  }
  return Status::ok();
}

}  // namespace

Status ShTripleProduct::make(int order, int transferOrder, ShTripleProduct* out) {
  if (order < 1 || order > kMaxTripleProductOrder) {
    return Status::error(StatusCode::kInvalidArgument, "triple-product order " + std::to_string(order) +
                                                           " is outside [1, " +
                                                           std::to_string(kMaxTripleProductOrder) + "]");
  }
  if (transferOrder < order || transferOrder > 2 * order - 1) {
    return Status::error(StatusCode::kInvalidArgument,
                         "triple-product transfer order " + std::to_string(transferOrder) + " is outside [" +
                             std::to_string(order) + ", " + std::to_string(2 * order - 1) + "] for order " +
                             std::to_string(order));
  }
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "no output tensor");
  const int n2 = shCoeffCount(order), m2 = shCoeffCount(transferOrder);
  out->order_ = order;
  out->transferOrder_ = transferOrder;
  out->entries_.clear();
  for (const ShTripleEntry& e : table().entries) {
    if (e.k >= m2) break;  // sorted by k first
    if (e.j < n2) out->entries_.push_back(e);
  }
  return Status::ok();
}

double ShTripleProduct::at(int i, int j, int k) const {
  int s[3] = {i, j, k};
  std::sort(s, s + 3);
  if (s[0] < 0 || s[1] >= shCoeffCount(order_) || s[2] >= shCoeffCount(transferOrder_)) return 0.0;
  // Entries are sorted by (k, j, i): compare keys in that order.
  const auto less = [](const ShTripleEntry& e, const int* key) {
    if (e.k != key[2]) return e.k < key[2];
    if (e.j != key[1]) return e.j < key[1];
    return e.i < key[0];
  };
  const auto it = std::lower_bound(entries_.begin(), entries_.end(), s, less);
  if (it == entries_.end() || it->i != s[0] || it->j != s[1] || it->k != s[2]) return 0.0;
  return it->value;
}

template <typename F>
void ShTripleProduct::forEachOrdered(F&& f) const {
  const int n2 = shCoeffCount(order_);
  for (const ShTripleEntry& e : entries_) {
    assert(e.j < n2 && e.k < shCoeffCount(transferOrder_));
    if (e.k < n2) {
      forEachPermutation(e, [&](int p, int q, int r) { f(p, q, r, e.value); });
    } else {
      // k is beyond the lighting's and output's range, so it can only sit in the third slot.
      f(e.i, e.j, e.k, e.value);
      if (e.i != e.j) f(e.j, e.i, e.k, e.value);
    }
  }
}

void ShTripleProduct::expand(std::vector<ShTripleEntry>* out) const {
  out->clear();
  forEachOrdered([&](int p, int q, int r, double v) {
    out->push_back({static_cast<std::uint16_t>(p), static_cast<std::uint16_t>(q), static_cast<std::uint16_t>(r), v});
  });
  std::sort(out->begin(), out->end(), [](const ShTripleEntry& x, const ShTripleEntry& y) {
    if (x.i != y.i) return x.i < y.i;
    if (x.k != y.k) return x.k < y.k;
    return x.j < y.j;
  });
}

void ShTripleProduct::productMatrixUnchecked(int lightingOrder, const float* lighting, float* out) const noexcept {
  assert(lightingOrder >= 1 && lightingOrder <= order_);
  const int m2 = shCoeffCount(transferOrder_);
  // Zero-padding the lighting to the tensor's order keeps the inner loop branch-free.
  float padded[shCoeffCount(kMaxTripleProductOrder)] = {};
  std::copy(lighting, lighting + shCoeffCount(lightingOrder), padded);
  std::fill(out, out + static_cast<std::size_t>(shCoeffCount(order_)) * m2, 0.0f);
  forEachOrdered([&](int i, int j, int k, double v) { out[i * m2 + k] += static_cast<float>(v) * padded[j]; });
}

Status ShTripleProduct::productMatrix(int lightingOrder, std::span<const float> lighting,
                                      std::span<float> out) const {
  if (order_ == 0) return Status::error(StatusCode::kInvalidArgument, "triple-product tensor not made");
  if (lightingOrder < 1 || lightingOrder > order_) {
    return Status::error(StatusCode::kInvalidArgument, "lighting order " + std::to_string(lightingOrder) +
                                                           " is outside [1, " + std::to_string(order_) +
                                                           "] (the tensor's order)");
  }
  const std::size_t nl = static_cast<std::size_t>(shCoeffCount(lightingOrder));
  PRT_RETURN_IF_ERROR(checkSize(lighting, nl, "lighting"));
  PRT_RETURN_IF_ERROR(checkFinite(lighting, nl, "lighting"));
  const std::size_t cells =
      static_cast<std::size_t>(shCoeffCount(order_)) * static_cast<std::size_t>(shCoeffCount(transferOrder_));
  if (out.size() < cells) {
    return Status::error(StatusCode::kSizeMismatch, "product matrix holds " + std::to_string(out.size()) +
                                                        " floats, " + std::to_string(cells) + " needed");
  }
  productMatrixUnchecked(lightingOrder, lighting.data(), out.data());
  return Status::ok();
}

Status ShTripleProduct::multiply(std::span<const float> a, std::span<const float> b, std::span<float> out) const {
  if (order_ == 0) return Status::error(StatusCode::kInvalidArgument, "triple-product tensor not made");
  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(order_));
  const std::size_t m2 = static_cast<std::size_t>(shCoeffCount(transferOrder_));
  PRT_RETURN_IF_ERROR(checkSize(a, n2, "first factor"));
  PRT_RETURN_IF_ERROR(checkSize(b, m2, "second factor"));
  if (out.size() < n2) {
    return Status::error(StatusCode::kSizeMismatch, "product holds " + std::to_string(out.size()) + " floats, " +
                                                        std::to_string(n2) + " needed");
  }
  PRT_RETURN_IF_ERROR(checkFinite(a, n2, "first factor"));
  PRT_RETURN_IF_ERROR(checkFinite(b, m2, "second factor"));
  double sum[shCoeffCount(kMaxTripleProductOrder)] = {};
  forEachOrdered([&](int i, int j, int k, double v) { sum[i] += v * a[j] * b[k]; });
  for (std::size_t i = 0; i < n2; ++i) out[i] = static_cast<float>(sum[i]);
  return Status::ok();
}

}  // namespace prt
