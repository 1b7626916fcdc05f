// The bounce gather's SIMD paths (baker/transfer/bounce_gather.h): every path this CPU runs
// gives the baseline path's bits, and the baseline is the sum it claims to be.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "baker/transfer/bounce_gather.h"

namespace prt::bake {
namespace {

bool sameBytes(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(BounceGather, EveryPathGivesTheSameBitsAndTheRightSum) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> dist(-1.0f, 1.0f);
  const std::vector<GatherPath> paths = availableGatherPaths();
  ASSERT_EQ(paths.front(), GatherPath::kDefault);
  const std::size_t vertexCount = 50, triangleCount = 40;
  std::vector<std::uint32_t> indices(3 * triangleCount);
  for (std::uint32_t& i : indices) i = static_cast<std::uint32_t>(rng() % vertexCount);
  // Strides of orders 2..8 (3 channels x order^2), odd ones included: every SIMD tail runs.
  for (const std::size_t stride : {12u, 27u, 48u, 75u, 108u, 147u, 192u}) {
    std::vector<float> previous(vertexCount * stride);
    for (float& p : previous) p = dist(rng);
    for (const std::size_t hitCount : {0u, 1u, 7u, 160u}) {
      std::vector<Hit> hits(hitCount);
      for (Hit& h : hits) {
        h.triangle = static_cast<std::uint32_t>(rng() % triangleCount);
        const std::uint32_t u = rng() % 65536, v = rng() % (65536 - u);  // inside the triangle
        h.u = static_cast<std::uint16_t>(u);
        h.v = static_cast<std::uint16_t>(v);
        h.weight = 0.5f * (dist(rng) + 1.0f);
      }
      std::vector<float> start(stride);
      for (float& s : start) s = dist(rng);  // gatherHits adds to what is there
      std::vector<float> reference = start;
      gatherHitsOn(GatherPath::kDefault, hits, indices.data(), previous.data(), stride, reference.data());
      for (std::size_t i = 0; i < stride; ++i) {
        double exact = start[i];
        for (const Hit& h : hits) {
          const double b1 = h.u / 65535.0, b2 = h.v / 65535.0, w[3] = {1.0 - b1 - b2, b1, b2};
          for (int c = 0; c < 3; ++c) exact += h.weight * w[c] * previous[indices[3 * h.triangle + c] * stride + i];
        }
        ASSERT_NEAR(reference[i], exact, 1e-5 * (1.0 + static_cast<double>(hitCount))) << stride << " " << i;
      }
      for (const GatherPath path : paths) {
        std::vector<float> out = start;
        gatherHitsOn(path, hits, indices.data(), previous.data(), stride, out.data());
        EXPECT_TRUE(sameBytes(out, reference)) << gatherPathName(path) << ", stride " << stride << ", " << hitCount << " hits";
      }
      std::vector<float> best = start;
      gatherHits(hits, indices.data(), previous.data(), stride, best.data());
      EXPECT_TRUE(sameBytes(best, reference)) << stride << " " << hitCount;
    }
  }
}

}  // namespace
}  // namespace prt::bake
