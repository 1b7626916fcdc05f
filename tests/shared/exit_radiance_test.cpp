// The shared exit-radiance reference (prt/exit_radiance.h) against sums written out by hand,
// and against the closed form of a clamped-cosine transfer under constant radiance.
#include "prt/exit_radiance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "prt/sh_basis.h"
#include "prt/sh_zonal.h"

namespace prt {
namespace {

TEST(ExitRadiance, ScalarTransferIsScaledByAlbedoAndRgbTransferIsNot) {
  // Two vertices, stride 4, lighting of 3 coefficients (the 4th stored one is not used).
  const std::vector<float> scalar = {1, 2, 3, 100, -1, 0.5f, 0, 100};
  const std::vector<Rgb> albedo = {{0.5f, 1, 0}, {1, 1, 1}};
  const std::vector<Rgb> light = {{1, 2, 3}, {10, 20, 30}, {100, 200, 300}};
  std::vector<float> out(6);
  ASSERT_TRUE(exitRadiance(scalar, 1, 4, albedo, light, out).isOk());
  // vertex 0: r = 0.5 (1 + 20 + 300), g = 1 (2 + 40 + 600), b = 0
  EXPECT_FLOAT_EQ(out[0], 0.5f * 321);
  EXPECT_FLOAT_EQ(out[1], 642);
  EXPECT_FLOAT_EQ(out[2], 0);
  EXPECT_FLOAT_EQ(out[3], -1 + 5);  // vertex 1: -1 + 0.5 * 10
  std::vector<float> noAlbedo(6);
  ASSERT_TRUE(exitRadiance(scalar, 1, 4, {}, light, noAlbedo).isOk());
  EXPECT_FLOAT_EQ(noAlbedo[0], 321);

  // One RGB vertex, stride 2, both coefficients used: each channel its own row.
  const std::vector<float> rgb = {1, 2, 3, 4, 5, 6};
  const std::vector<Rgb> light2 = {{1, 1, 1}, {10, 100, 1000}};
  std::vector<double> d(3);
  ASSERT_TRUE(exitRadianceDouble(rgb, 3, 2, std::vector<Rgb>{{0, 0, 0}}, light2, d).isOk());
  EXPECT_DOUBLE_EQ(d[0], 1 + 20);
  EXPECT_DOUBLE_EQ(d[1], 3 + 400);
  EXPECT_DOUBLE_EQ(d[2], 5 + 6000);
}

TEST(ExitRadiance, ClampedCosineUnderConstantRadianceIsAlbedo) {
  // T = (1/pi) max(0, n.w) projected: under radiance 1 the exit radiance is 1 x albedo.
  const int order = 3;
  std::vector<float> zonal(order), placed(order * order);
  ASSERT_TRUE(zonalClampedCosine(order, zonal).isOk());
  ASSERT_TRUE(placeZonal(order, zonal, {0.6f, 0.0f, 0.8f}, placed).isOk());
  for (float& t : placed) t /= static_cast<float>(kPi);
  std::vector<Rgb> light(order * order);
  const float l0 = static_cast<float>(2.0 * std::sqrt(kPi));
  light[0] = {l0, l0, l0};
  std::vector<float> f(3);
  std::vector<double> d(3);
  const std::vector<Rgb> albedo = {{0.25f, 0.5f, 1}};
  ASSERT_TRUE(exitRadiance(placed, 1, order * order, albedo, light, f).isOk());
  ASSERT_TRUE(exitRadianceDouble(placed, 1, order * order, albedo, light, d).isOk());
  EXPECT_NEAR(f[0], 0.25, 1e-6);
  EXPECT_NEAR(f[2], 1.0, 1e-6);
  EXPECT_NEAR(d[1], 0.5, 1e-6);
}

TEST(ExitRadiance, BadShapesAreRefused) {
  const std::vector<float> t(8, 1.0f);
  const std::vector<Rgb> light(2);
  std::vector<float> out(6);
  EXPECT_EQ(exitRadiance(t, 2, 4, {}, light, out).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(exitRadiance(t, 1, 1, {}, light, out).code(), StatusCode::kInvalidArgument);  // 2 > stride 1
  EXPECT_EQ(exitRadiance(t, 1, 4, {}, light, std::span<float>(out.data(), 3)).code(), StatusCode::kSizeMismatch);
  EXPECT_EQ(exitRadiance(t, 1, 4, std::vector<Rgb>(3), light, out).code(), StatusCode::kSizeMismatch);
  EXPECT_TRUE(exitRadiance(t, 1, 4, std::vector<Rgb>(2), light, out).isOk());
}

}  // namespace
}  // namespace prt
