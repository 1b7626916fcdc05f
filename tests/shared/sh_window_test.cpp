#include "prt/sh_window.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "prt/sh_basis.h"
#include "prt/sh_zonal.h"

namespace prt {
namespace {

TEST(ShWindow, NoneIsIdentity) {
  std::vector<float> w(8);
  ASSERT_TRUE(shWindowWeights(ShWindow::kNone, 8, 0.0f, w).isOk());
  for (float v : w) EXPECT_EQ(v, 1.0f);
}

TEST(ShWindow, WindowsStartAtOneAndFallMonotonically) {
  for (ShWindow win : {ShWindow::kHanning, ShWindow::kLanczos}) {
    std::vector<float> w(8);
    ASSERT_TRUE(shWindowWeights(win, 8, 0.0f, w).isOk());
    EXPECT_EQ(w[0], 1.0f);
    for (int l = 1; l < 8; ++l) {
      EXPECT_LT(w[l], w[l - 1]) << shWindowName(win) << " l=" << l;
      EXPECT_GT(w[l], 0.0f) << "default width keeps every band";
    }
  }
  std::vector<float> w(4);
  ASSERT_TRUE(shWindowWeights(ShWindow::kHanning, 4, 2.0f, w).isOk());
  EXPECT_NEAR(w[1], 0.5f, 1e-6f);  // (1 + cos(pi/2)) / 2
  EXPECT_EQ(w[2], 0.0f);
  EXPECT_EQ(w[3], 0.0f);
}

// Windowing exists to reduce ringing: a small bright disc, truncated at order 6, overshoots
// into negative radiance opposite it; the Hanning window must reduce that.
TEST(ShWindow, HanningReducesNegativeRinging) {
  const int order = 6;
  std::vector<float> zonal(order), coeffs(shCoeffCount(order));
  ASSERT_TRUE(zonalCircularLight(order, 0.2f, 1.0f, zonal).isOk());
  ASSERT_TRUE(placeZonal(order, zonal, {0, 0, 1}, coeffs).isOk());
  auto minimum = [&](const std::vector<Rgb>& c) {
    float lowest = 1e9f;
    std::vector<float> y(shCoeffCount(order));
    for (int k = 0; k <= 180; ++k) {
      const float theta = static_cast<float>(kPi) * k / 180.0f;
      evalShBasisUnchecked(order, {std::sin(theta), 0, std::cos(theta)}, y.data());
      float v = 0;
      for (int i = 0; i < shCoeffCount(order); ++i) v += c[i].r * y[i];
      lowest = std::fmin(lowest, v);
    }
    return lowest;
  };
  std::vector<Rgb> plain(coeffs.size()), windowed(coeffs.size());
  for (std::size_t i = 0; i < coeffs.size(); ++i) plain[i] = windowed[i] = {coeffs[i], coeffs[i], coeffs[i]};
  ASSERT_TRUE(applyShWindow(ShWindow::kHanning, order, 0.0f, windowed).isOk());
  EXPECT_LT(minimum(plain), -0.005f) << "the test needs visible ringing to be meaningful";
  EXPECT_GT(minimum(windowed), 0.5f * minimum(plain));
  EXPECT_FLOAT_EQ(windowed[0].r, plain[0].r) << "the DC term (total power) is kept";
}

TEST(ShWindow, ParsesNames) {
  ShWindow w = ShWindow::kNone;
  EXPECT_TRUE(parseShWindow("lanczos", &w).isOk());
  EXPECT_EQ(w, ShWindow::kLanczos);
  const Status bad = parseShWindow("gauss", &w);
  EXPECT_FALSE(bad.isOk());
  EXPECT_NE(bad.message().find("gauss"), std::string::npos);
}

}  // namespace
}  // namespace prt
