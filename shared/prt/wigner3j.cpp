#include "prt/wigner3j.h"

#include <cmath>
#include <limits>

#include "prt/vec3.h"

namespace prt {
namespace {

constexpr int kMaxFactorial = 3 * kMaxWignerJ + 1;

// n! in double for 0 <= n <= kMaxFactorial. Exact up to 22!; above that the rounding
// (relative 1e-16) is far below the cancellation error of the Racah sum.
double factorial(int n) {
  static const struct Table {
    double v[kMaxFactorial + 1];
    Table() {
      v[0] = 1.0;
      for (int i = 1; i <= kMaxFactorial; ++i) v[i] = v[i - 1] * i;
    }
  } table;
  return table.v[n];
}

int maxOf(int a, int b, int c) { return a > b ? (a > c ? a : c) : (b > c ? b : c); }
int minOf(int a, int b, int c) { return a < b ? (a < c ? a : c) : (b < c ? b : c); }

}  // namespace

double wigner3j(int j1, int j2, int j3, int m1, int m2, int m3) {
  if (j1 < 0 || j2 < 0 || j3 < 0 || j1 > kMaxWignerJ || j2 > kMaxWignerJ || j3 > kMaxWignerJ) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (m1 + m2 + m3 != 0) return 0.0;
  if (m1 > j1 || -m1 > j1 || m2 > j2 || -m2 > j2 || m3 > j3 || -m3 > j3) return 0.0;
  if (j3 > j1 + j2 || j3 < (j1 > j2 ? j1 - j2 : j2 - j1)) return 0.0;
  // Racah's formula (e.g. Edmonds 3.7.3, in 3j form): a sum over k of
  // (-1)^k / [k! (j3-j2+k+m1)! (j3-j1+k-m2)! (j1+j2-j3-k)! (j1-k-m1)! (j2-k+m2)!],
  // over the k that keep every factorial argument non-negative.
  const int kMin = maxOf(0, j2 - j3 - m1, j1 - j3 + m2);
  const int kMax = minOf(j1 + j2 - j3, j1 - m1, j2 + m2);
  double sum = 0.0;
  for (int k = kMin; k <= kMax; ++k) {
    const double term = 1.0 / (factorial(k) * factorial(j3 - j2 + k + m1) * factorial(j3 - j1 + k - m2) *
                               factorial(j1 + j2 - j3 - k) * factorial(j1 - k - m1) * factorial(j2 - k + m2));
    sum += (k % 2 == 0) ? term : -term;
  }
  const double triangle = factorial(j1 + j2 - j3) * factorial(j1 - j2 + j3) * factorial(-j1 + j2 + j3) /
                          factorial(j1 + j2 + j3 + 1);
  const double norm = factorial(j1 + m1) * factorial(j1 - m1) * factorial(j2 + m2) * factorial(j2 - m2) *
                      factorial(j3 + m3) * factorial(j3 - m3);
  const int phase = j1 - j2 - m3;
  const double sign = (phase % 2 == 0) ? 1.0 : -1.0;
  return sign * std::sqrt(triangle * norm) * sum;
}

double complexGaunt(int l1, int l2, int l3, int m1, int m2, int m3) {
  const double w000 = wigner3j(l1, l2, l3, 0, 0, 0);
  if (std::isnan(w000)) return w000;
  if (w000 == 0.0) return 0.0;  // l1+l2+l3 odd or triangle violated
  const double wm = wigner3j(l1, l2, l3, m1, m2, m3);
  if (wm == 0.0) return 0.0;
  return std::sqrt((2.0 * l1 + 1.0) * (2.0 * l2 + 1.0) * (2.0 * l3 + 1.0) / (4.0 * kPi)) * w000 * wm;
}

}  // namespace prt
