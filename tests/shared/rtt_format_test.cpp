// Radiance transfer texture files and view map (prt/rtt.h): the hemisphere map's geometry
// (unit, upper, equal-area, inverted by rttViewCoordinates) and the reader on damaged bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "prt/bi_scale.h"
#include "prt/rtt.h"

namespace prt {
namespace {

TEST(RttViewMap, DirectionsAreUnitUpperAndInvert) {
  EXPECT_FLOAT_EQ(rttViewDirection(0, 0, 1).z, 1.0f);
  for (int views : {1, 2, 3, 8, 32}) {
    for (int b = 0; b < views; ++b) {
      for (int a = 0; a < views; ++a) {
        const Vec3 w = rttViewDirection(a, b, views);
        EXPECT_NEAR(length(w), 1.0f, 1e-5f);
        EXPECT_GT(w.z, 0.0f);
        float u = -1, v = -1;
        rttViewCoordinates(w, views, &u, &v);
        EXPECT_NEAR(u, a + 0.5f, 2e-4f * views) << "view " << a << "," << b << " of " << views;
        EXPECT_NEAR(v, b + 0.5f, 2e-4f * views) << "view " << a << "," << b << " of " << views;
      }
    }
  }
}

// Equal area: directions uniform over the hemisphere (z uniform, azimuth uniform) fall into
// the 8 x 8 view cells in equal shares.
TEST(RttViewMap, CellsCoverEqualSolidAngles) {
  constexpr int kViews = 8, kSamples = 256000;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<int> count(kViews * kViews, 0);
  for (int i = 0; i < kSamples; ++i) {
    const float z = unit(rng), phi = 6.2831853f * unit(rng), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    float a = 0, b = 0;
    rttViewCoordinates({r * std::cos(phi), r * std::sin(phi), z}, kViews, &a, &b);
    const int ia = std::min(kViews - 1, static_cast<int>(a)), ib = std::min(kViews - 1, static_cast<int>(b));
    ++count[ib * kViews + ia];
  }
  const double expected = static_cast<double>(kSamples) / (kViews * kViews);  // 4000, sigma about 63
  for (int c : count) EXPECT_NEAR(c, expected, 0.08 * expected);
}

// rttLookup: nearest spatial sample, bilinear across views, the centre view when view
// dependence is off. Coefficient 0 encodes (x, y, a, b) linearly, so bilinear is exact.
TEST(RttLookup, NearestInSpaceBilinearInView) {
  Rtt r;
  r.order = 1;
  r.channels = 1;
  r.spatial = 4;
  r.views = 4;
  r.coeffs.resize(r.coeffCount());
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) r.coeffs[static_cast<std::size_t>(((y * 4 + x) * 4 + b) * 4 + a)] = 1000.0f * y + 100.0f * x + 10.0f * b + a;
  float out = 0;
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      rttLookup(r, (2 + 0.3f) / 4, (1 + 0.9f) / 4, rttViewDirection(a, b, 4), true, &out);
      EXPECT_NEAR(out, 1000.0f + 200.0f + 10.0f * b + a, 2e-3f) << "view " << a << "," << b;
    }
  rttLookup(r, 1.0f + 0.1f / 4, -1.0f + 3.5f / 4, {0, 0, 1}, false, &out);  // wraps: x 0, y 3
  EXPECT_NEAR(out, 3000.0f + 15.0f + 1.5f, 1e-3f) << "the centre view: between samples 1 and 2 both ways";
  // The direction halfway between samples (1, 2) and (2, 2): on the square's middle column
  // (a = 2, halfway between their centres 1.5 and 2.5), its b wherever the map puts it.
  float a = 0, b = 0;
  const Vec3 mid = rttViewDirection(1, 2, 4) + rttViewDirection(2, 2, 4);
  rttViewCoordinates(mid * (1.0f / length(mid)), 4, &a, &b);
  rttLookup(r, 0.1f, 0.1f, mid * (1.0f / length(mid)), true, &out);
  EXPECT_NEAR(a, 2.0f, 1e-4f);
  EXPECT_NEAR(out, 10.0f * (b - 0.5f) + 1.5f, 2e-3f);
}

Rtt smallRtt() {
  Rtt r;
  r.order = 2;
  r.channels = 3;
  r.spatial = 2;
  r.views = 2;
  r.coeffs.resize(r.coeffCount());
  for (std::size_t i = 0; i < r.coeffs.size(); ++i) r.coeffs[i] = 0.01f * static_cast<float>(i) - 1.0f;
  return r;
}

TEST(RttFile, RoundTrips) {
  const Rtt r = smallRtt();
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(encodeRtt(r, &bytes).isOk());
  EXPECT_EQ(bytes.size(), 40u + 4u * r.coeffs.size() + 4u);
  Rtt back;
  ASSERT_TRUE(decodeRtt(bytes, &back).isOk());
  EXPECT_EQ(back.order, 2);
  EXPECT_EQ(back.channels, 3);
  EXPECT_EQ(back.spatial, 2);
  EXPECT_EQ(back.views, 2);
  EXPECT_EQ(back.coeffs, r.coeffs);
}

TEST(RttFile, EncoderRefusesInconsistentShapes) {
  Rtt r = smallRtt();
  std::vector<std::uint8_t> bytes;
  r.coeffs.pop_back();
  EXPECT_EQ(encodeRtt(r, &bytes).code(), StatusCode::kInvalidArgument);
  r = smallRtt();
  r.channels = 2;
  EXPECT_EQ(encodeRtt(r, &bytes).code(), StatusCode::kInvalidArgument);
}

TEST(RttFile, EveryPrefixAndByteFlipIsRefused) {
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(encodeRtt(smallRtt(), &bytes).isOk());
  Rtt out;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_FALSE(decodeRtt(std::span<const std::uint8_t>(bytes.data(), n), &out).isOk()) << "prefix of " << n << " bytes";
  }
  std::vector<std::uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_EQ(decodeRtt(longer, &out).code(), StatusCode::kCorrupt);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    for (std::uint8_t bit : {0x01, 0x80}) {
      std::vector<std::uint8_t> damaged = bytes;
      damaged[i] ^= bit;
      EXPECT_FALSE(decodeRtt(damaged, &out).isOk()) << "byte " << i << " bit " << int(bit);
    }
  }
  std::vector<std::uint8_t> version = bytes;
  version[8] = 2;
  EXPECT_EQ(decodeRtt(version, &out).code(), StatusCode::kBadVersion);
  std::vector<std::uint8_t> magic = bytes;
  magic[0] = 'X';
  EXPECT_EQ(decodeRtt(magic, &out).code(), StatusCode::kBadMagic);
}

// A header whose shape would need more coefficients than any file holds is refused by its
// ranges before any size arithmetic.
TEST(RttFile, OutOfRangeHeaderIsCorrupt) {
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(encodeRtt(smallRtt(), &bytes).isOk());
  Rtt out;
  std::vector<std::uint8_t> huge = bytes;
  huge[20] = 0xff;
  huge[21] = 0xff;  // spatial 65535 + ...
  EXPECT_EQ(decodeRtt(huge, &out).code(), StatusCode::kCorrupt);
}

}  // namespace
}  // namespace prt
