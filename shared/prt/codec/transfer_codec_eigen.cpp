#include "transfer_codec_eigen.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace prt::transfer_codec {

SymmetricEigen symmetricEigen(int n, std::vector<double> a) {
  const std::size_t N = static_cast<std::size_t>(n);
  auto at = [&](std::size_t i, std::size_t j) -> double& { return a[i * N + j]; };
  for (std::size_t i = 0; i < N; ++i) {
    for (std::size_t j = i + 1; j < N; ++j) at(i, j) = at(j, i) = 0.5 * (at(i, j) + at(j, i));
  }
  std::vector<double> v(N * N, 0.0);  // accumulated rotations; column j -> eigenvector j
  for (std::size_t i = 0; i < N; ++i) v[i * N + i] = 1.0;

  double scale = 0.0;
  for (double x : a) scale = std::max(scale, std::fabs(x));
  // Cyclic sweeps until the off-diagonal part is negligible against the largest entry.
  for (int sweep = 0; sweep < 100 && scale > 0.0; ++sweep) {
    double off = 0.0;
    for (std::size_t i = 0; i < N; ++i) {
      for (std::size_t j = i + 1; j < N; ++j) off += at(i, j) * at(i, j);
    }
    if (off <= 1e-30 * scale * scale) break;
    for (std::size_t p = 0; p < N; ++p) {
      for (std::size_t q = p + 1; q < N; ++q) {
        const double apq = at(p, q);
        if (std::fabs(apq) <= 1e-300) continue;
        // Rotation that zeroes a_pq (Golub & Van Loan, Algorithm 8.4.1, sym.schur2).
        const double tau = (at(q, q) - at(p, p)) / (2.0 * apq);
        const double t = (tau >= 0.0 ? 1.0 : -1.0) / (std::fabs(tau) + std::sqrt(1.0 + tau * tau));
        const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
        for (std::size_t k = 0; k < N; ++k) {  // A <- A J (columns p, q)
          const double akp = at(k, p), akq = at(k, q);
          at(k, p) = c * akp - s * akq;
          at(k, q) = s * akp + c * akq;
        }
        for (std::size_t k = 0; k < N; ++k) {  // A <- J^T A (rows p, q)
          const double apk = at(p, k), aqk = at(q, k);
          at(p, k) = c * apk - s * aqk;
          at(q, k) = s * apk + c * aqk;
        }
        at(p, q) = at(q, p) = 0.0;
        for (std::size_t k = 0; k < N; ++k) {  // V <- V J
          const double vkp = v[k * N + p], vkq = v[k * N + q];
          v[k * N + p] = c * vkp - s * vkq;
          v[k * N + q] = s * vkp + c * vkq;
        }
      }
    }
  }

  std::vector<std::size_t> order(N);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return at(x, x) > at(y, y); });
  SymmetricEigen r;
  r.values.resize(N);
  r.vectors.resize(N * N);
  for (std::size_t j = 0; j < N; ++j) {
    const std::size_t col = order[j];
    r.values[j] = at(col, col);
    std::size_t big = 0;
    for (std::size_t i = 1; i < N; ++i) {
      if (std::fabs(v[i * N + col]) > std::fabs(v[big * N + col])) big = i;
    }
    const double sign = v[big * N + col] < 0.0 ? -1.0 : 1.0;
    for (std::size_t i = 0; i < N; ++i) r.vectors[j * N + i] = sign * v[i * N + col];
  }
  return r;
}

}  // namespace prt::transfer_codec
