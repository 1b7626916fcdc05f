#include "support/quadrature.h"

#include <cmath>

namespace prt::ref {

void gaussLegendre(int n, std::vector<double>* nodes, std::vector<double>* weights) {
  nodes->assign(n, 0.0);
  weights->assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = n == 0 ? 1.0 : (n == 1 ? x : p1);
      const double pnm1 = n == 1 ? 1.0 : p0;
      dp = n * (x * pn - pnm1) / (x * x - 1.0);
      const double dx = pn / dp;
      x -= dx;
      if (std::fabs(dx) < 1e-15) break;
    }
    (*nodes)[i] = x;
    (*weights)[i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
}

std::vector<WeightedDirection> sphereQuadrature(int n) {
  std::vector<double> z, w;
  gaussLegendre(n, &z, &w);
  const int nphi = 2 * n;
  std::vector<WeightedDirection> out;
  out.reserve(static_cast<std::size_t>(n) * nphi);
  for (int i = 0; i < n; ++i) {
    const double r = std::sqrt(std::fmax(0.0, 1.0 - z[i] * z[i]));
    for (int j = 0; j < nphi; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / nphi;
      out.push_back({{static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)), static_cast<float>(z[i])},
                     w[i] * 2.0 * kPi / nphi});
    }
  }
  return out;
}

}  // namespace prt::ref
