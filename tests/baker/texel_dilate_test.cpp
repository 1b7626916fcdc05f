// Gutter dilation (baker/texture/texel_dilate.h): used texels never change; unused texels
// within N texels (Chebyshev) of a used one are filled with convex combinations of used
// values, those further away are untouched; a constant stays exactly constant; the averaging
// rule itself on a case small enough to work by hand; after rasterisation and one pass, a
// bilinear fetch anywhere inside a triangle reads only filled texels; bad arguments are errors.
#include "baker/texture/texel_dilate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "baker/texture/texel_raster.h"

namespace prt::bake {
namespace {

constexpr float kUntouched = -7.0f;  // what unused texels hold before dilation

// An irregular chart: an L-shaped block plus an isolated texel, in a w × h texture.
std::vector<std::uint8_t> chartCoverage(int w, int h) {
  std::vector<std::uint8_t> c(static_cast<std::size_t>(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool block = x >= 4 && x < 10 && y >= 3 && y < 8 && !(x >= 7 && y >= 5);
      const bool single = x == 15 && y == 12;
      c[static_cast<std::size_t>(y) * w + x] = block || single ? 1 : 0;
    }
  return c;
}

// Chebyshev distance from texel (x, y) to the nearest used texel (brute force).
int distanceToUsed(const std::vector<std::uint8_t>& coverage, int w, int h, int x, int y) {
  int best = std::numeric_limits<int>::max();
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      if (coverage[static_cast<std::size_t>(v) * w + u])
        best = std::min(best, std::max(std::abs(u - x), std::abs(v - y)));
  return best;
}

TEST(TexelDilate, FillsWithinNWithConvexCombinationsAndLeavesTheRest) {
  const int w = 20, h = 16, channels = 2, passes = 3;
  const std::vector<std::uint8_t> coverage = chartCoverage(w, h);
  // Used texels hold (r, 1 - r): a convex combination of them must keep the sum at 1 and each
  // channel within the used range.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.1f, 0.9f);
  std::vector<float> tex(static_cast<std::size_t>(w) * h * channels, kUntouched);
  float lo = 1, hi = 0;
  for (std::size_t i = 0; i < coverage.size(); ++i) {
    if (!coverage[i]) continue;
    const float r = unit(rng);
    tex[2 * i] = r;
    tex[2 * i + 1] = 1.0f - r;
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  const std::vector<float> before = tex;
  std::vector<std::uint8_t> filled;
  ASSERT_TRUE(dilateGutters(tex, w, h, channels, coverage, passes, &filled).isOk());
  ASSERT_EQ(filled.size(), coverage.size());
  int filledCount = 0, untouchedCount = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      const int d = distanceToUsed(coverage, w, h, x, y);
      SCOPED_TRACE("texel " + std::to_string(x) + "," + std::to_string(y) + " at distance " + std::to_string(d));
      if (d == 0) {
        EXPECT_EQ(std::memcmp(&tex[2 * i], &before[2 * i], 2 * sizeof(float)), 0) << "a used texel changed";
        EXPECT_EQ(filled[i], 1);
      } else if (d <= passes) {
        ++filledCount;
        EXPECT_EQ(filled[i], 1);
        EXPECT_GE(tex[2 * i], lo);
        EXPECT_LE(tex[2 * i], hi);
        EXPECT_NEAR(tex[2 * i] + tex[2 * i + 1], 1.0f, 1e-6f);
      } else {
        ++untouchedCount;
        EXPECT_EQ(filled[i], 0);
        EXPECT_EQ(tex[2 * i], kUntouched);
        EXPECT_EQ(tex[2 * i + 1], kUntouched);
      }
    }
  }
  EXPECT_GT(filledCount, 50);
  EXPECT_GT(untouchedCount, 50);
}

TEST(TexelDilate, ConstantStaysExactlyConstant) {
  const int w = 20, h = 16, passes = 4;
  const std::vector<std::uint8_t> coverage = chartCoverage(w, h);
  const float c = 0.3f;  // not a dyadic fraction: an average in float could round it
  std::vector<float> tex(coverage.size(), kUntouched);
  for (std::size_t i = 0; i < coverage.size(); ++i)
    if (coverage[i]) tex[i] = c;
  ASSERT_TRUE(dilateGutters(tex, w, h, 1, coverage, passes).isOk());
  int filled = 0;
  for (float v : tex) {
    if (v == kUntouched) continue;
    EXPECT_EQ(v, c);
    ++filled;
  }
  EXPECT_GT(filled, 100);
}

TEST(TexelDilate, AveragesTheFilledNeighboursOfThePreviousPass) {
  // 5 × 1: used 1 at x = 0 and 3 at x = 2. Pass 1: x = 1 -> (1 + 3) / 2 = 2, x = 3 -> 3.
  // Pass 2: x = 4 -> 3 (its only neighbour, filled in pass 1).
  std::vector<float> tex{1, kUntouched, 3, kUntouched, kUntouched};
  const std::vector<std::uint8_t> coverage{1, 0, 1, 0, 0};
  std::vector<float> one = tex;
  ASSERT_TRUE(dilateGutters(one, 5, 1, 1, coverage, 1).isOk());
  EXPECT_EQ(one, (std::vector<float>{1, 2, 3, 3, kUntouched}));
  ASSERT_TRUE(dilateGutters(tex, 5, 1, 1, coverage, 2).isOk());
  EXPECT_EQ(tex, (std::vector<float>{1, 2, 3, 3, 3}));
  // In 2D all 8 neighbours count: the centre of a 3 × 3 with used corners 0, 4, 8, 12.
  std::vector<float> grid{0, kUntouched, 4, kUntouched, kUntouched, kUntouched, 8, kUntouched, 12};
  const std::vector<std::uint8_t> corners{1, 0, 1, 0, 0, 0, 1, 0, 1};
  ASSERT_TRUE(dilateGutters(grid, 3, 3, 1, corners, 1).isOk());
  EXPECT_EQ(grid[4], 6.0f);
  EXPECT_EQ(grid[1], 2.0f);
}

TEST(TexelDilate, ZeroPassesAndNoUsedTexelsChangeNothing) {
  const std::vector<std::uint8_t> coverage = chartCoverage(20, 16);
  std::vector<float> tex(coverage.size(), kUntouched);
  for (std::size_t i = 0; i < coverage.size(); ++i)
    if (coverage[i]) tex[i] = 1.5f;
  const std::vector<float> before = tex;
  ASSERT_TRUE(dilateGutters(tex, 20, 16, 1, coverage, 0).isOk());
  EXPECT_EQ(tex, before);
  std::vector<float> empty(coverage.size(), kUntouched);
  ASSERT_TRUE(dilateGutters(empty, 20, 16, 1, std::vector<std::uint8_t>(coverage.size(), 0), 5).isOk());
  EXPECT_EQ(empty, std::vector<float>(coverage.size(), kUntouched));
}

TEST(TexelDilate, OnePassAfterRasterisationFeedsEveryBilinearFetchInsideTheChart) {
  // A chart of two triangles away from the atlas border, rasterised at 40 × 32. A bilinear
  // fetch at UV point p reads the four texels around p - 0.5; without dilation some of those
  // are outside the coverage, after one pass none are.
  const int w = 40, h = 32;
  const std::vector<Vec3> positions{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5f}};
  const std::vector<Vec3> normals(4, Vec3{0, 0, 1});
  const std::vector<Uv> uvs{{0.12f, 0.17f}, {0.81f, 0.23f}, {0.67f, 0.86f}, {0.21f, 0.74f}};
  const std::vector<std::uint32_t> indices{0, 1, 2, 0, 2, 3};
  TexelRaster r;
  ASSERT_TRUE(rasteriseTexels(positions, normals, indices, uvs, w, h, &r).isOk());
  std::vector<float> tex(r.coverage.size(), kUntouched);
  for (const TexelSample& s : r.samples) tex[s.texel] = s.position.z;
  std::vector<std::uint8_t> filled;
  ASSERT_TRUE(dilateGutters(tex, w, h, 1, r.coverage, 1, &filled).isOk());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int missedBefore = 0;
  for (int i = 0; i < 4000; ++i) {
    // A uniform point of triangle i % 2, in texel units.
    double a = unit(rng), b = unit(rng);
    if (a + b > 1) {
      a = 1 - a;
      b = 1 - b;
    }
    const Uv p0 = uvs[indices[3 * (i % 2)]], p1 = uvs[indices[3 * (i % 2) + 1]], p2 = uvs[indices[3 * (i % 2) + 2]];
    const double px = (p0.u + a * (p1.u - p0.u) + b * (p2.u - p0.u)) * w;
    const double py = (p0.v + a * (p1.v - p0.v) + b * (p2.v - p0.v)) * h;
    const int x0 = static_cast<int>(std::floor(px - 0.5)), y0 = static_cast<int>(std::floor(py - 0.5));
    for (int dy = 0; dy <= 1; ++dy)
      for (int dx = 0; dx <= 1; ++dx) {
        const std::size_t t = static_cast<std::size_t>(y0 + dy) * w + static_cast<std::size_t>(x0 + dx);
        missedBefore += r.coverage[t] ? 0 : 1;
        ASSERT_EQ(filled[t], 1) << "bilinear fetch at (" << px << ", " << py << ") reads an empty texel";
        ASSERT_NE(tex[t], kUntouched);
      }
  }
  EXPECT_GT(missedBefore, 0) << "the fetches near the chart's edges do reach outside the coverage";
}

TEST(TexelDilate, BadArgumentsAreErrorsAndLeaveTheTextureAlone) {
  const std::vector<std::uint8_t> coverage{1, 0, 0, 0};
  std::vector<float> tex{1, 0, 0, 0};
  auto code = [&](std::vector<float>& t, int w, int h, int c, const std::vector<std::uint8_t>& cov, int p) {
    const std::vector<float> before = t;
    const Status s = dilateGutters(t, w, h, c, cov, p);
    // Bytes, not values: NaN != NaN.
    if (!s.isOk()) {
      EXPECT_EQ(std::memcmp(t.data(), before.data(), t.size() * sizeof(float)), 0) << s.toString();
    }
    return s.code();
  };
  EXPECT_EQ(code(tex, 2, 2, 1, coverage, 1), StatusCode::kOk);
  tex = {1, 0, 0, 0};
  EXPECT_EQ(code(tex, 2, 2, 2, coverage, 1), StatusCode::kSizeMismatch);
  EXPECT_EQ(code(tex, 4, 1, 1, std::vector<std::uint8_t>{1, 0}, 1), StatusCode::kSizeMismatch);
  EXPECT_EQ(code(tex, 2, 2, 0, coverage, 1), StatusCode::kInvalidArgument);
  EXPECT_EQ(code(tex, 2, 2, 1, coverage, -1), StatusCode::kInvalidArgument);
  EXPECT_EQ(code(tex, 2, 2, 1, coverage, kMaxDilationPasses + 1), StatusCode::kInvalidArgument);
  EXPECT_EQ(code(tex, 0, 4, 1, coverage, 1), StatusCode::kInvalidArgument);
  EXPECT_EQ(code(tex, 16385, 1, 1, coverage, 1), StatusCode::kInvalidArgument);
  std::vector<float> nan{std::numeric_limits<float>::quiet_NaN(), 0, 0, 0};
  EXPECT_EQ(code(nan, 2, 2, 1, coverage, 1), StatusCode::kNotFinite);
  // NaN in an unused texel is only background, and gets overwritten.
  std::vector<float> background{2, std::numeric_limits<float>::quiet_NaN(), 0, 0};
  EXPECT_EQ(code(background, 2, 2, 1, coverage, 1), StatusCode::kOk);
  EXPECT_EQ(background, (std::vector<float>{2, 2, 2, 2}));
}

}  // namespace
}  // namespace prt::bake
