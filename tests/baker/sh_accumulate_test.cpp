// The direct pass's SH projection (baker/transfer/sh_accumulate.h): every SIMD path this CPU
// runs gives the scalar order's bits, and that order sums the right terms (a double reference).
#include "baker/transfer/sh_accumulate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace prt::bake {
namespace {

bool sameBytes(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(ShAccumulate, EverySimdPathGivesTheSameBits) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> dist(-1.0f, 1.0f);
  const std::vector<SimdPath> paths = availableSimdPaths();
  ASSERT_EQ(paths.front(), SimdPath::kScalar);
  for (const std::size_t count : {1u, 16u, 31u, 32u, 33u, 100u, 1000u, 1024u}) {
    const int n2 = 25;
    std::vector<float> weights(count), basis(n2 * count);
    for (float& w : weights) w = dist(rng) > 0.0f ? dist(rng) : 0.0f;  // zeros, as below the horizon
    for (float& b : basis) b = dist(rng);
    std::vector<float> reference(n2);
    projectWeightsOn(SimdPath::kScalar, n2, count, weights.data(), basis.data(), reference.data());
    for (int i = 0; i < n2; ++i) {  // the scalar order is a sum of the right terms
      double exact = 0.0;
      for (std::size_t k = 0; k < count; ++k) exact += static_cast<double>(weights[k]) * basis[i * count + k];
      ASSERT_NEAR(reference[i], exact, 1e-5 * std::sqrt(static_cast<double>(count))) << count << " " << i;
    }
    for (const SimdPath path : paths) {
      std::vector<float> out(n2);
      projectWeightsOn(path, n2, count, weights.data(), basis.data(), out.data());
      EXPECT_TRUE(sameBytes(out, reference)) << simdPathName(path) << ", " << count << " samples";
    }
    std::vector<float> best(n2);
    projectWeights(n2, count, weights.data(), basis.data(), best.data());
    EXPECT_TRUE(sameBytes(best, reference)) << count;
  }
}

}  // namespace
}  // namespace prt::bake
