#include "prt/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "prt/sh_project.h"

namespace prt {
namespace {

void expectUniformOnSphere(const DirectionSet& s, double tolerance) {
  double mx = 0, my = 0, mz = 0, zz = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    ASSERT_NEAR(length(s.at(k)), 1.0f, 1e-5f);
    mx += s.x[k];
    my += s.y[k];
    mz += s.z[k];
    zz += static_cast<double>(s.z[k]) * s.z[k];
  }
  const double n = static_cast<double>(s.size());
  EXPECT_NEAR(mx / n, 0.0, tolerance);
  EXPECT_NEAR(my / n, 0.0, tolerance);
  EXPECT_NEAR(mz / n, 0.0, tolerance);
  EXPECT_NEAR(zz / n, 1.0 / 3.0, tolerance);  // E[z^2] on the uniform sphere
  EXPECT_NEAR(s.weight * n, 4.0 * kPi, 1e-9);
}

TEST(Sampling, HammersleyIsUniformAndDeterministic) {
  DirectionSet a, b;
  ASSERT_TRUE(hammersleySphere(4096, &a).isOk());
  ASSERT_TRUE(hammersleySphere(4096, &b).isOk());
  expectUniformOnSphere(a, 2e-3);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.z, b.z);
}

TEST(Sampling, StratifiedIsUniformAndSeeded) {
  DirectionSet a, b, c;
  ASSERT_TRUE(stratifiedSphere(64, 1, &a).isOk());
  ASSERT_TRUE(stratifiedSphere(64, 1, &b).isOk());
  ASSERT_TRUE(stratifiedSphere(64, 2, &c).isOk());
  expectUniformOnSphere(a, 5e-3);
  EXPECT_EQ(a.x, b.x);
  EXPECT_NE(a.x, c.x);
}

TEST(Sampling, Pcg32ReferenceSequence) {
  // The stream must be identical natively and in wasm; the values pin the algorithm.
  Pcg32 rng(42);
  std::uint32_t first[3] = {rng.next(), rng.next(), rng.next()};
  Pcg32 again(42);
  for (std::uint32_t v : first) EXPECT_EQ(again.next(), v);
  Pcg32 other(43);
  EXPECT_NE(other.next(), first[0]);
}

TEST(Sampling, MonteCarloProjectionConvergesForSmoothFunctions) {
  // f = 1 + x: c00 = 2 sqrt(pi), c(1,1) = 4pi/3 * sqrt(3/4pi) = 2 sqrt(pi/3).
  DirectionSet s;
  ASSERT_TRUE(hammersleySphere(1 << 14, &s).isOk());
  std::vector<Rgb> values(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) values[k] = {1.0f + s.x[k], 1.0f, 1.0f};
  std::vector<Rgb> c;
  ASSERT_TRUE(projectSamples(3, s, values, &c).isOk());
  EXPECT_NEAR(c[0].r, 2.0 * std::sqrt(kPi), 1e-3);
  EXPECT_NEAR(c[3].r, 2.0 * std::sqrt(kPi / 3.0), 2e-3);
  EXPECT_NEAR(c[1].r, 0.0, 2e-3);
  EXPECT_NEAR(c[3].g, 0.0, 2e-3);
}

}  // namespace
}  // namespace prt
