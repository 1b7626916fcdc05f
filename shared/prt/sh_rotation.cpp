#include "prt/sh_rotation.h"

#include <cmath>
#include <string>

#include "prt/sh_basis.h"

namespace prt {
namespace {

// Dense (2l+1)x(2l+1) band matrix indexed by m, n in [-l, l].
struct Band {
  int l = 0;
  std::vector<double> v;
  explicit Band(int band) : l(band), v(static_cast<std::size_t>((2 * band + 1) * (2 * band + 1)), 0.0) {}
  double& operator()(int m, int n) { return v[(m + l) * (2 * l + 1) + (n + l)]; }
  double operator()(int m, int n) const { return v[(m + l) * (2 * l + 1) + (n + l)]; }
};

// Ivanic & Ruedenberg's helper P (their Table 2, corrected): r1 is the band-1 matrix,
// prev the band l-1 matrix.
double funcP(int i, int a, int b, int l, const Band& r1, const Band& prev) {
  if (b == l) return r1(i, 1) * prev(a, l - 1) - r1(i, -1) * prev(a, -l + 1);
  if (b == -l) return r1(i, 1) * prev(a, -l + 1) + r1(i, -1) * prev(a, l - 1);
  return r1(i, 0) * prev(a, b);
}

double funcU(int m, int n, int l, const Band& r1, const Band& prev) { return funcP(0, m, n, l, r1, prev); }

double funcV(int m, int n, int l, const Band& r1, const Band& prev) {
  if (m == 0) return funcP(1, 1, n, l, r1, prev) + funcP(-1, -1, n, l, r1, prev);
  if (m > 0) {
    const double d = m == 1 ? 1.0 : 0.0;
    return funcP(1, m - 1, n, l, r1, prev) * std::sqrt(1.0 + d) - funcP(-1, -m + 1, n, l, r1, prev) * (1.0 - d);
  }
  const double d = m == -1 ? 1.0 : 0.0;
  return funcP(1, m + 1, n, l, r1, prev) * (1.0 - d) + funcP(-1, -m - 1, n, l, r1, prev) * std::sqrt(1.0 + d);
}

double funcW(int m, int n, int l, const Band& r1, const Band& prev) {
  if (m > 0) return funcP(1, m + 1, n, l, r1, prev) + funcP(-1, -m - 1, n, l, r1, prev);
  return funcP(1, m - 1, n, l, r1, prev) - funcP(-1, -m + 1, n, l, r1, prev);  // m < 0 (m == 0 has w = 0)
}

Status checkRotation(const Mat3& r) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!std::isfinite(r.m[i][j])) return Status::error(StatusCode::kNotFinite, "rotation matrix is not finite");
  double worst = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double d = 0.0;
      for (int k = 0; k < 3; ++k) d += static_cast<double>(r.m[k][i]) * r.m[k][j];
      worst = std::fmax(worst, std::fabs(d - (i == j ? 1.0 : 0.0)));
    }
  }
  const double det = r.m[0][0] * (static_cast<double>(r.m[1][1]) * r.m[2][2] - static_cast<double>(r.m[1][2]) * r.m[2][1]) -
                     r.m[0][1] * (static_cast<double>(r.m[1][0]) * r.m[2][2] - static_cast<double>(r.m[1][2]) * r.m[2][0]) +
                     r.m[0][2] * (static_cast<double>(r.m[1][0]) * r.m[2][1] - static_cast<double>(r.m[1][1]) * r.m[2][0]);
  if (worst > 1e-3 || std::fabs(det - 1.0) > 1e-3) {
    return Status::error(StatusCode::kInvalidArgument,
                         "matrix is not a rotation (|R^T R - I| = " + std::to_string(worst) +
                             ", det = " + std::to_string(det) + ")");
  }
  return Status::ok();
}

}  // namespace

Status ShRotation::make(int order, const Mat3& r, ShRotation* out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (Status s = checkRotation(r); !s.isOk()) return s;
  out->order_ = order;
  out->values_.assign(static_cast<std::size_t>(offset(order)), 0.0f);
  out->values_[0] = 1.0f;
  if (order == 1) return Status::ok();

  // Band 1: y_1m ~ (y, z, x) for m = -1, 0, 1, so D^1 is R with rows/columns permuted.
  const int axis[3] = {1, 2, 0};  // m = -1 -> y, 0 -> z, 1 -> x
  Band r1(1);
  for (int m = -1; m <= 1; ++m)
    for (int n = -1; n <= 1; ++n) r1(m, n) = r.m[axis[m + 1]][axis[n + 1]];

  Band prev = r1;
  auto store = [out](const Band& b) {
    for (int m = -b.l; m <= b.l; ++m)
      for (int n = -b.l; n <= b.l; ++n)
        out->values_[offset(b.l) + (m + b.l) * (2 * b.l + 1) + (n + b.l)] = static_cast<float>(b(m, n));
  };
  store(r1);
  for (int l = 2; l < order; ++l) {
    Band cur(l);
    for (int m = -l; m <= l; ++m) {
      const int am = m < 0 ? -m : m;
      for (int n = -l; n <= l; ++n) {
        const int an = n < 0 ? -n : n;
        const double denom = an == l ? (2.0 * l) * (2.0 * l - 1.0) : static_cast<double>(l + n) * (l - n);
        const double d = m == 0 ? 1.0 : 0.0;
        const double u = std::sqrt(static_cast<double>(l + m) * (l - m) / denom);
        const double v = 0.5 * std::sqrt((1.0 + d) * (l + am - 1.0) * (l + am) / denom) * (1.0 - 2.0 * d);
        const double w = -0.5 * std::sqrt((l - am - 1.0) * (l - am) / denom) * (1.0 - d);
        double value = 0.0;
        if (u != 0.0) value += u * funcU(m, n, l, r1, prev);
        if (v != 0.0) value += v * funcV(m, n, l, r1, prev);
        if (w != 0.0) value += w * funcW(m, n, l, r1, prev);
        cur(m, n) = value;
      }
    }
    store(cur);
    prev = std::move(cur);
  }
  return Status::ok();
}

// Band-by-band product out = D in, for scalar or RGB coefficients (T + T * float).
template <typename T>
Status ShRotation::applyTo(std::span<const T> in, std::span<T> out) const {
  const std::size_t n = static_cast<std::size_t>(shCoeffCount(order_));
  if (order_ == 0) return Status::error(StatusCode::kInvalidArgument, "rotation was not built");
  if (in.size() < n || out.size() < n) {
    return Status::error(StatusCode::kSizeMismatch, "coefficient arrays must hold " + std::to_string(n) + " values");
  }
  for (int l = 0; l < order_; ++l) {
    for (int m = -l; m <= l; ++m) {
      T acc{};
      for (int k = -l; k <= l; ++k) acc = acc + in[shIndex(l, k)] * at(l, m, k);
      out[shIndex(l, m)] = acc;
    }
  }
  return Status::ok();
}

Status ShRotation::apply(std::span<const float> in, std::span<float> out) const { return applyTo(in, out); }
Status ShRotation::apply(std::span<const Rgb> in, std::span<Rgb> out) const { return applyTo(in, out); }

}  // namespace prt
