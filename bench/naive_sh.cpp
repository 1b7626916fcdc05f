#include "naive_sh.h"

#include <cmath>

namespace prt::bench {
namespace {

constexpr double kPi = 3.14159265358979323846;

double factorial(int n) {
  double f = 1.0;
  for (int k = 2; k <= n; ++k) f *= k;
  return f;
}

// K_lm = sqrt((2l+1)/(4 pi) (l-|m|)!/(l+|m|)!), factorials computed on every call.
double norm(int l, int am) {
  return std::sqrt((2.0 * l + 1.0) / (4.0 * kPi) * factorial(l - am) / factorial(l + am));
}

// Associated Legendre P_l^m(x), 0 <= m <= l, without the Condon-Shortley phase:
//   P_m^m     = (2m-1)!! (1-x^2)^(m/2)
//   P_{m+1}^m = x (2m+1) P_m^m
//   P_l^m     = ((2l-1) x P_{l-1}^m - (l+m-1) P_{l-2}^m) / (l-m)
double legendre(int l, int m, double x) {
  const double s = std::sqrt((1.0 - x) * (1.0 + x));
  double pmm = 1.0;
  for (int k = 1; k <= m; ++k) pmm *= (2.0 * k - 1.0) * s;
  if (l == m) return pmm;
  double pm1 = x * (2.0 * m + 1.0) * pmm;
  if (l == m + 1) return pm1;
  double p2 = pmm, p1 = pm1, pl = 0.0;
  for (int ll = m + 2; ll <= l; ++ll) {
    pl = ((2.0 * ll - 1.0) * x * p1 - (ll + m - 1.0) * p2) / (ll - m);
    p2 = p1;
    p1 = pl;
  }
  return pl;
}

}  // namespace

double naiveShValue(int l, int m, double theta, double phi) {
  const double cosTheta = std::cos(theta);
  if (m == 0) return norm(l, 0) * legendre(l, 0, cosTheta);
  const int am = m < 0 ? -m : m;
  const double trig = m > 0 ? std::cos(am * phi) : std::sin(am * phi);
  return std::sqrt(2.0) * norm(l, am) * trig * legendre(l, am, cosTheta);
}

void naiveShEval(int order, double x, double y, double z, float* out) {
  const double ct = z < -1.0 ? -1.0 : (z > 1.0 ? 1.0 : z);  // float inputs may overshoot 1
  const double theta = std::acos(ct);
  const double phi = std::atan2(y, x);
  for (int l = 0; l < order; ++l) {
    for (int m = -l; m <= l; ++m) {
      out[l * (l + 1) + m] = static_cast<float>(naiveShValue(l, m, theta, phi));
    }
  }
}

}  // namespace prt::bench
