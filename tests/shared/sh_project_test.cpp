#include "prt/sh_project.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "prt/sh_basis.h"
#include "support/quadrature.h"

namespace prt {
namespace {

// Direction of an equirectangular pixel centre, written out independently of the library.
Vec3 equirectDir(int i, int j, int w, int h) {
  const double phi = 2.0 * kPi * ((i + 0.5) / w - 0.5);
  const double lat = 0.5 * kPi - kPi * (j + 0.5) / h;
  return {static_cast<float>(std::cos(lat) * std::cos(phi)), static_cast<float>(std::sin(lat)),
          static_cast<float>(std::cos(lat) * std::sin(phi))};
}

RgbImage makeEquirect(int w, int h, const std::function<Rgb(Vec3)>& f) {
  RgbImage img;
  img.width = w;
  img.height = h;
  img.rgb.resize(static_cast<std::size_t>(w) * h * 3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const Rgb c = f(equirectDir(i, j, w, h));
      float* p = &img.rgb[(static_cast<std::size_t>(j) * w + i) * 3];
      p[0] = c.r;
      p[1] = c.g;
      p[2] = c.b;
    }
  return img;
}

RgbImage makeAngular(int n, const std::function<Rgb(Vec3)>& f) {
  RgbImage img;
  img.width = img.height = n;
  img.rgb.assign(static_cast<std::size_t>(n) * n * 3, 0.0f);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = -1.0 + 2.0 * (i + 0.5) / n, v = 1.0 - 2.0 * (j + 0.5) / n, r = std::sqrt(u * u + v * v);
      const double theta = kPi * std::fmin(r, 1.0);
      Vec3 d{static_cast<float>(std::sin(theta) * u / r), static_cast<float>(std::sin(theta) * v / r),
             static_cast<float>(std::cos(theta))};
      const Rgb c = f(d * (1.0f / length(d)));
      float* p = &img.rgb[(static_cast<std::size_t>(j) * n + i) * 3];
      p[0] = c.r;
      p[1] = c.g;
      p[2] = c.b;
    }
  return img;
}

std::vector<float> bandLimitedTruth(int order) {
  std::vector<float> truth(shCoeffCount(order));
  for (int i = 0; i < shCoeffCount(order); ++i) truth[i] = std::cos(2.3f * i + 0.1f);
  return truth;
}

Rgb evalTruth(const std::vector<float>& truth, int order, Vec3 d) {
  std::vector<float> y(shCoeffCount(order));
  evalShBasisUnchecked(order, d, y.data());
  float v = 0;
  for (int i = 0; i < shCoeffCount(order); ++i) v += truth[i] * y[i];
  return {v, 2 * v, 0};
}

TEST(Projection, ExactQuadratureReconstructsBandLimitedFunctions) {
  // Projection then reconstruction of a band-limited function is exact.
  const int order = 8;
  const auto truth = bandLimitedTruth(order);
  ShProjector p;
  ASSERT_TRUE(ShProjector::make(order, &p).isOk());
  for (const auto& q : ref::sphereQuadrature(order + 1)) {
    const Vec3 d = q.dir * (1.0f / length(q.dir));
    p.add(d, evalTruth(truth, order, d), q.weight);
  }
  EXPECT_NEAR(p.weightSum(), 4.0 * kPi, 1e-9);
  const auto c = p.coefficients();
  for (int i = 0; i < shCoeffCount(order); ++i) {
    EXPECT_NEAR(c[i].r, truth[i], 2e-5) << "i=" << i;
    EXPECT_NEAR(c[i].g, 2 * truth[i], 4e-5);
    EXPECT_NEAR(c[i].b, 0.0f, 1e-7);
  }
  // And the expansion evaluates back to the function.
  Rgb v;
  ASSERT_TRUE(evalShExpansion(order, c, {0.2f, -0.4f, 0.7f}, &v).isOk());
  EXPECT_NEAR(v.r, evalTruth(truth, order, Vec3{0.2f, -0.4f, 0.7f} * (1.0f / length({0.2f, -0.4f, 0.7f}))).r, 1e-4);
}

TEST(Projection, EquirectConstantGivesDcOnly) {
  std::vector<Rgb> c;
  ASSERT_TRUE(projectEquirect(5, makeEquirect(256, 128, [](Vec3) { return Rgb{1, 1, 1}; }), &c).isOk());
  EXPECT_NEAR(c[0].r, 2.0 * std::sqrt(kPi), 1e-5);  // row weights are exact solid angles
  for (std::size_t i = 1; i < c.size(); ++i) EXPECT_NEAR(c[i].r, 0.0, 5e-4) << i;
}

TEST(Projection, EquirectReproducesABandLimitedFunction) {
  const int order = 5;
  const auto truth = bandLimitedTruth(order);
  std::vector<Rgb> c;
  ASSERT_TRUE(projectEquirect(order, makeEquirect(512, 256, [&](Vec3 d) { return evalTruth(truth, order, d); }), &c).isOk());
  for (int i = 0; i < shCoeffCount(order); ++i) EXPECT_NEAR(c[i].r, truth[i], 2e-3) << i;
}

TEST(Projection, EquirectOrientation) {
  // Bright band around u = 0.75 (longitude +90 degrees) lies toward +z; top rows toward +y.
  RgbImage img = makeEquirect(64, 32, [](Vec3) { return Rgb{0, 0, 0}; });
  img.rgb[(static_cast<std::size_t>(16) * 64 + 48) * 3] = 100.0f;  // row 16 (equator), column 48 (u = 0.76)
  img.rgb[(static_cast<std::size_t>(0) * 64 + 5) * 3 + 1] = 100.0f;   // top row, green
  std::vector<Rgb> c;
  ASSERT_TRUE(projectEquirect(2, img, &c).isOk());
  EXPECT_GT(c[shIndex(1, 0)].r, 10.0f * std::fabs(c[shIndex(1, 1)].r));  // red toward +z
  EXPECT_GT(c[shIndex(1, -1)].g, 10.0f * std::fabs(c[shIndex(1, 0)].g));  // green toward +y
}

TEST(Projection, AngularMapReproducesABandLimitedFunction) {
  const int order = 4;
  const auto truth = bandLimitedTruth(order);
  std::vector<Rgb> c;
  ASSERT_TRUE(projectAngularMap(order, makeAngular(512, [&](Vec3 d) { return evalTruth(truth, order, d); }), &c).isOk());
  for (int i = 0; i < shCoeffCount(order); ++i) EXPECT_NEAR(c[i].r, truth[i], 1e-2) << i;
  std::vector<Rgb> k;
  ASSERT_TRUE(projectAngularMap(1, makeAngular(512, [](Vec3) { return Rgb{1, 1, 1}; }), &k).isOk());
  EXPECT_NEAR(k[0].r, 2.0 * std::sqrt(kPi), 5e-3);
}

TEST(Projection, AngularMapCentreLooksAlongPlusZ) {
  RgbImage img = makeAngular(64, [](Vec3) { return Rgb{0, 0, 0}; });
  img.rgb[(static_cast<std::size_t>(32) * 64 + 32) * 3] = 100.0f;
  std::vector<Rgb> c;
  ASSERT_TRUE(projectAngularMap(2, img, &c).isOk());
  EXPECT_GT(c[shIndex(1, 0)].r, 0.0f);
  EXPECT_GT(c[shIndex(1, 0)].r, 10.0f * std::fabs(c[shIndex(1, 1)].r));
}

}  // namespace
}  // namespace prt
