#include "prt/sh_rotation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "prt/sh_basis.h"
#include "prt/sampling.h"
#include "support/quadrature.h"

namespace prt {
namespace {

std::vector<Mat3> testRotations() {
  std::vector<Mat3> rs = {Mat3{}, rotationAxisAngle({0, 0, 1}, 0.7f), rotationAxisAngle({0, 1, 0}, 2.1f),
                          rotationAxisAngle({1, 0, 0}, static_cast<float>(kPi)),  // 180 degrees
                          rotationAxisAngle({0, 1, 0}, static_cast<float>(kPi / 2))};  // Euler gimbal case
  Pcg32 rng(7);
  for (int k = 0; k < 6; ++k) {
    rs.push_back(rotationAxisAngle(squareToSphere(rng.nextFloat(), rng.nextFloat()), 6.2f * rng.nextFloat()));
  }
  return rs;
}

std::vector<float> randomCoefficients(int order, std::uint64_t seed) {
  Pcg32 rng(seed);
  std::vector<float> c(shCoeffCount(order));
  for (float& v : c) v = 2.0f * rng.nextFloat() - 1.0f;
  return c;
}

double evalExpansion(int order, const std::vector<float>& c, Vec3 d) {
  std::vector<float> y(shCoeffCount(order));
  evalShBasisUnchecked(order, d * (1.0f / length(d)), y.data());
  double s = 0.0;
  for (int i = 0; i < shCoeffCount(order); ++i) s += c[i] * y[i];
  return s;
}

TEST(ShRotation, RotatingCoefficientsEqualsProjectingTheRotatedFunction) {
  const int order = 8;
  const auto quad = ref::sphereQuadrature(order + 1);  // exact for the product of two band-limited functions
  const std::vector<float> c = randomCoefficients(order, 99);
  for (const Mat3& r : testRotations()) {
    ShRotation rot;
    ASSERT_TRUE(ShRotation::make(order, r, &rot).isOk());
    std::vector<float> rotated(c.size());
    ASSERT_TRUE(rot.apply(c, rotated).isOk());
    // Project f'(u) = f(R^T u).
    const Mat3 rt = transpose(r);
    std::vector<double> projected(c.size(), 0.0);
    std::vector<float> y(c.size());
    for (const auto& q : quad) {
      const Vec3 u = q.dir * (1.0f / length(q.dir));
      const double f = evalExpansion(order, c, rt * u);
      evalShBasisUnchecked(order, u, y.data());
      for (std::size_t i = 0; i < c.size(); ++i) projected[i] += q.weight * f * y[i];
    }
    for (std::size_t i = 0; i < c.size(); ++i) ASSERT_NEAR(rotated[i], projected[i], 2e-4) << "i=" << i;
  }
}

TEST(ShRotation, ComposesAsMatrixProduct) {
  const int order = 7;
  const auto rs = testRotations();
  const std::vector<float> c = randomCoefficients(order, 3);
  for (std::size_t k = 0; k + 1 < rs.size(); ++k) {
    ShRotation a, b, ab;
    ASSERT_TRUE(ShRotation::make(order, rs[k], &a).isOk());
    ASSERT_TRUE(ShRotation::make(order, rs[k + 1], &b).isOk());
    ASSERT_TRUE(ShRotation::make(order, rs[k] * rs[k + 1], &ab).isOk());
    std::vector<float> t(c.size()), twoStep(c.size()), oneStep(c.size());
    ASSERT_TRUE(b.apply(c, t).isOk());
    ASSERT_TRUE(a.apply(t, twoStep).isOk());
    ASSERT_TRUE(ab.apply(c, oneStep).isOk());
    for (std::size_t i = 0; i < c.size(); ++i) ASSERT_NEAR(twoStep[i], oneStep[i], 2e-5);
  }
}

TEST(ShRotation, BandMatricesAreOrthogonal) {
  const int order = kMaxShOrder;
  for (const Mat3& r : testRotations()) {
    ShRotation rot;
    ASSERT_TRUE(ShRotation::make(order, r, &rot).isOk());
    for (int l = 0; l < order; ++l) {
      for (int m1 = -l; m1 <= l; ++m1) {
        for (int m2 = -l; m2 <= l; ++m2) {
          double dotp = 0.0;
          for (int n = -l; n <= l; ++n) dotp += static_cast<double>(rot.at(l, m1, n)) * rot.at(l, m2, n);
          ASSERT_NEAR(dotp, m1 == m2 ? 1.0 : 0.0, 1e-4) << "l=" << l;
        }
      }
    }
  }
}

TEST(ShRotation, ZRotationMatchesClosedForm) {
  // About z the pair (y_l,m ~ cos m phi, y_l,-m ~ sin m phi) turns by m*alpha:
  // f(R^T u) with f = cos(m phi) is cos(m(phi - alpha)).
  const float alpha = 0.9f;
  const int order = 9;
  ShRotation rot;
  ASSERT_TRUE(ShRotation::make(order, rotationAxisAngle({0, 0, 1}, alpha), &rot).isOk());
  for (int l = 0; l < order; ++l) {
    for (int m = -l; m <= l; ++m) {
      for (int n = -l; n <= l; ++n) {
        double expected = 0.0;
        const int am = std::abs(m);
        if (m == 0 && n == 0) expected = 1.0;
        else if (m != 0 && n == m) expected = std::cos(am * alpha);
        else if (m > 0 && n == -m) expected = -std::sin(am * alpha);
        else if (m < 0 && n == -m) expected = std::sin(am * alpha);
        ASSERT_NEAR(rot.at(l, m, n), expected, 2e-5) << "l=" << l << " m=" << m << " n=" << n;
      }
    }
  }
}

TEST(ShRotation, RotatesRgbChannelsIndependently) {
  const int order = 4;
  const Mat3 r = rotationAxisAngle({1, 2, 3}, 1.3f);
  ShRotation rot;
  ASSERT_TRUE(ShRotation::make(order, r, &rot).isOk());
  const auto cr = randomCoefficients(order, 1), cg = randomCoefficients(order, 2), cb = randomCoefficients(order, 3);
  std::vector<Rgb> in(cr.size()), out(cr.size());
  for (std::size_t i = 0; i < cr.size(); ++i) in[i] = {cr[i], cg[i], cb[i]};
  ASSERT_TRUE(rot.apply(std::span<const Rgb>(in), std::span<Rgb>(out)).isOk());
  std::vector<float> rr(cr.size());
  ASSERT_TRUE(rot.apply(cg, rr).isOk());
  for (std::size_t i = 0; i < cr.size(); ++i) EXPECT_FLOAT_EQ(out[i].g, rr[i]);
}

TEST(ShRotation, PointLobeFollowsTheRotation) {
  // A zonal lobe about +z rotated by R peaks at R * z.
  const int order = 6;
  std::vector<float> c(shCoeffCount(order), 0.0f);
  evalShBasisUnchecked(order, {0, 0, 1}, c.data());  // delta function at +z, band-limited
  const Mat3 r = rotationAxisAngle({1, 1, 0}, 1.0f);
  ShRotation rot;
  ASSERT_TRUE(ShRotation::make(order, r, &rot).isOk());
  std::vector<float> out(c.size());
  ASSERT_TRUE(rot.apply(c, out).isOk());
  const Vec3 peak = r * Vec3{0, 0, 1};
  EXPECT_NEAR(evalExpansion(order, out, peak), evalExpansion(order, c, {0, 0, 1}), 1e-4);
  EXPECT_GT(evalExpansion(order, out, peak), evalExpansion(order, out, {0, 0, 1}) + 0.5);
}

}  // namespace
}  // namespace prt
