#include "prt/sh_zonal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "prt/sh_basis.h"
#include "support/quadrature.h"

namespace prt {
namespace {

// Brute-force SH projection of a function that is non-zero only within angle acos(tMin)
// of `axis`: Gauss-Legendre in t = u.axis over [tMin, 1] times many azimuths about the axis.
// Independent of the zonal formulas and of the addition theorem.
std::vector<double> projectAroundAxis(int order, Vec3 axis, double tMin, const std::function<double(double)>& h) {
  axis = axis * (1.0f / length(axis));
  Vec3 t1 = std::fabs(axis.x) < 0.9f ? cross(axis, {1, 0, 0}) : cross(axis, {0, 1, 0});
  t1 = t1 * (1.0f / length(t1));
  const Vec3 t2 = cross(axis, t1);
  std::vector<double> nodes, weights;
  ref::gaussLegendre(48, &nodes, &weights);
  const int nphi = 96;
  std::vector<double> c(shCoeffCount(order), 0.0);
  std::vector<float> y(shCoeffCount(order));
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double t = tMin + (1.0 - tMin) * 0.5 * (nodes[i] + 1.0);
    const double wt = weights[i] * 0.5 * (1.0 - tMin);
    const double s = std::sqrt(std::fmax(0.0, 1.0 - t * t));
    for (int j = 0; j < nphi; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / nphi;
      Vec3 u = axis * static_cast<float>(t) + t1 * static_cast<float>(s * std::cos(phi)) + t2 * static_cast<float>(s * std::sin(phi));
      u = u * (1.0f / length(u));
      evalShBasisUnchecked(order, u, y.data());
      const double w = wt * 2.0 * kPi / nphi * h(t);
      for (int k = 0; k < shCoeffCount(order); ++k) c[k] += w * y[k];
    }
  }
  return c;
}

TEST(Zonal, ClampedCosineHMatchesIntegralAndKnownValues) {
  const int order = 12;
  std::vector<double> h(order);
  ASSERT_TRUE(clampedCosineH(order, h).isOk());
  EXPECT_DOUBLE_EQ(h[0], 1.0);
  EXPECT_DOUBLE_EQ(h[1], 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(h[2], 1.0 / 4.0);   // Ramamoorthi & Hanrahan: A_2 = pi/4
  EXPECT_DOUBLE_EQ(h[4], -1.0 / 24.0);  // A_4 = -pi/24
  EXPECT_DOUBLE_EQ(h[6], 1.0 / 64.0);
  // H_l = 2 int_0^1 z P_l(z) dz by Gauss-Legendre (exact for these polynomials).
  std::vector<double> nodes, weights;
  ref::gaussLegendre(16, &nodes, &weights);
  for (int l = 0; l < order; ++l) {
    double integral = 0.0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const double z = 0.5 * (nodes[i] + 1.0);
      double p0 = 1.0, p1 = z, pl = l == 0 ? 1.0 : z;
      for (int k = 2; k <= l; ++k) {
        pl = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = pl;
      }
      integral += weights[i] * 0.5 * 2.0 * z * pl;
    }
    EXPECT_NEAR(h[l], integral, 1e-12) << "l=" << l;
  }
}

TEST(Zonal, ClampedCosineMatchesBruteForceOnAnyAxis) {
  const int order = 8;
  std::vector<float> zonal(order), placed(shCoeffCount(order));
  ASSERT_TRUE(zonalClampedCosine(order, zonal).isOk());
  for (Vec3 axis : {Vec3{0, 0, 1}, Vec3{0.3f, -0.5f, 0.81f}, Vec3{-1, 0.2f, -0.1f}}) {
    ASSERT_TRUE(placeZonal(order, zonal, axis, placed).isOk());
    const auto brute = projectAroundAxis(order, axis, 0.0, [](double t) { return t; });
    for (int i = 0; i < shCoeffCount(order); ++i) EXPECT_NEAR(placed[i], brute[i], 2e-5) << "i=" << i;
  }
}

TEST(Zonal, CircularLightMatchesBruteForce) {
  const int order = 8;
  for (float zeta : {0.05f, 0.3f, 1.0f, 2.0f, static_cast<float>(kPi)}) {
    std::vector<float> zonal(order), placed(shCoeffCount(order));
    ASSERT_TRUE(zonalCircularLight(order, zeta, 2.5f, zonal).isOk());
    const Vec3 axis{0.2f, 0.9f, -0.3f};
    ASSERT_TRUE(placeZonal(order, zonal, axis, placed).isOk());
    const auto brute = projectAroundAxis(order, axis, std::cos(static_cast<double>(zeta)), [](double) { return 2.5; });
    for (int i = 0; i < shCoeffCount(order); ++i) EXPECT_NEAR(placed[i], brute[i], 3e-5) << "zeta=" << zeta << " i=" << i;
  }
}

TEST(Zonal, FullSphereLightIsConstant) {
  // zeta = pi covers the sphere: only the DC term survives, 4pi * radiance * y00.
  std::vector<float> zonal(6);
  ASSERT_TRUE(zonalCircularLight(6, static_cast<float>(kPi), 1.0f, zonal).isOk());
  EXPECT_NEAR(zonal[0], 2.0 * std::sqrt(kPi), 1e-5);
  for (int l = 1; l < 6; ++l) EXPECT_NEAR(zonal[l], 0.0, 1e-5);
}

TEST(Zonal, ConvolutionTurnsConstantRadianceIntoIrradiancePi) {
  // Irradiance from constant unit radiance is pi everywhere.
  const int order = 3;
  std::vector<float> kernel(order), coeffs(shCoeffCount(order), 0.0f);
  ASSERT_TRUE(zonalClampedCosine(order, kernel).isOk());
  coeffs[0] = static_cast<float>(2.0 * std::sqrt(kPi));
  ASSERT_TRUE(convolveZonal(order, kernel, coeffs).isOk());
  EXPECT_NEAR(coeffs[0] * 0.2820948f, kPi, 1e-5);
}

}  // namespace
}  // namespace prt
