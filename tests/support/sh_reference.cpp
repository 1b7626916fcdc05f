#include "support/sh_reference.h"

#include <cmath>
#include <cstdlib>
#include <vector>

namespace prt::ref {
namespace {

double factorial(int n) {
  double f = 1.0;
  for (int k = 2; k <= n; ++k) f *= k;
  return f;
}

double binomial(int n, int k) { return factorial(n) / (factorial(k) * factorial(n - k)); }

// m-th derivative of the Legendre polynomial P_l at x, from the explicit sum
// P_l(x) = 2^-l sum_k (-1)^k C(l,k) C(2l-2k, l) x^(l-2k).
double legendreDerivative(int l, int m, double x) {
  double sum = 0.0;
  for (int k = 0; 2 * k <= l; ++k) {
    const int power = l - 2 * k;
    if (power < m) continue;
    double coeff = (k % 2 ? -1.0 : 1.0) * binomial(l, k) * binomial(2 * l - 2 * k, l);
    for (int d = 0; d < m; ++d) coeff *= (power - d);
    sum += coeff * std::pow(x, power - m);
  }
  return sum / std::pow(2.0, l);
}

}  // namespace

double shTextbook(int l, int m, double x, double y, double z) {
  const int am = std::abs(m);
  const double theta = std::atan2(std::sqrt(x * x + y * y), z);
  const double phi = std::atan2(y, x);
  const double ct = std::cos(theta), st = std::sin(theta);
  const double plm = std::pow(st, am) * legendreDerivative(l, am, ct);
  const double k = std::sqrt((2.0 * l + 1.0) / (4.0 * kPi) * factorial(l - am) / factorial(l + am));
  if (m == 0) return k * plm;
  if (m > 0) return std::sqrt(2.0) * k * std::cos(am * phi) * plm;
  return std::sqrt(2.0) * k * std::sin(am * phi) * plm;
}

double shFujitaTable3(int l, int m, double x, double y, double z) {
  const double pi = kPi;
  switch (l * 100 + (m + 50)) {
    case 0 * 100 + 50: return std::sqrt(1.0 / (4 * pi));
    case 1 * 100 + 49: return std::sqrt(3.0 / (4 * pi)) * y;
    case 1 * 100 + 50: return std::sqrt(3.0 / (4 * pi)) * z;
    case 1 * 100 + 51: return std::sqrt(3.0 / (4 * pi)) * x;
    case 2 * 100 + 48: return std::sqrt(15.0 / (4 * pi)) * x * y;
    case 2 * 100 + 49: return std::sqrt(15.0 / (4 * pi)) * y * z;
    case 2 * 100 + 50: return std::sqrt(5.0 / (16 * pi)) * (3 * z * z - 1);
    case 2 * 100 + 51: return std::sqrt(15.0 / (4 * pi)) * x * z;
    case 2 * 100 + 52: return std::sqrt(15.0 / (16 * pi)) * (x * x - y * y);
    case 3 * 100 + 47: return std::sqrt(35.0 / (32 * pi)) * (3 * x * x * y - y * y * y);
    case 3 * 100 + 48: return std::sqrt(105.0 / (4 * pi)) * x * y * z;
    case 3 * 100 + 49: return std::sqrt(21.0 / (32 * pi)) * y * (5 * z * z - 1);
    case 3 * 100 + 50: return std::sqrt(7.0 / (16 * pi)) * (5 * z * z * z - 3 * z);
    case 3 * 100 + 51: return std::sqrt(21.0 / (32 * pi)) * x * (5 * z * z - 1);
    case 3 * 100 + 52: return std::sqrt(105.0 / (16 * pi)) * z * (x * x - y * y);
    case 3 * 100 + 53: return std::sqrt(35.0 / (32 * pi)) * (x * x * x - 3 * x * y * y);
    case 4 * 100 + 46: return std::sqrt(315.0 / (16 * pi)) * (x * x * x * y - x * y * y * y);
    case 4 * 100 + 47: return std::sqrt(315.0 / (32 * pi)) * z * (3 * x * x * y - y * y * y);
    case 4 * 100 + 48: return std::sqrt(45.0 / (16 * pi)) * x * y * (7 * z * z - 1);
    case 4 * 100 + 49: return std::sqrt(45.0 / (32 * pi)) * (7 * y * z * z * z - 3 * y * z);
    case 4 * 100 + 50: return std::sqrt(9.0 / (256 * pi)) * (35 * z * z * z * z - 30 * z * z + 3);
    case 4 * 100 + 51: return std::sqrt(45.0 / (32 * pi)) * (7 * x * z * z * z - 3 * x * z);
    case 4 * 100 + 52: return std::sqrt(45.0 / (64 * pi)) * (x * x - y * y) * (7 * z * z - 1);
    case 4 * 100 + 53: return std::sqrt(315.0 / (32 * pi)) * z * (x * x * x - 3 * x * y * y);
    case 4 * 100 + 54: return std::sqrt(315.0 / (256 * pi)) * (x * x * x * x - 6 * x * x * y * y + y * y * y * y);
    default: std::abort();  // the table stops at l = 4
  }
}

}  // namespace prt::ref
