// The bounce gather's SIMD paths (baker/transfer/bounce_gather.h): every path this CPU runs
// gives the baseline path's bits, the baseline is the sum it claims to be, and a vertex
// receiver's terms are its hits' corners in order.
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
  const std::size_t rowCount = 50;
  // Strides of orders 2..8 (3 channels x order^2): whole chunks and tails on every path.
  for (const std::size_t stride : {12u, 27u, 48u, 75u, 108u, 147u, 192u}) {
    std::vector<float> previous(rowCount * stride);
    for (float& p : previous) p = dist(rng);
    for (const std::size_t termCount : {0u, 1u, 11u, 13u, 480u}) {  // below and past the prefetch distance
      WeightedRows terms;
      for (std::size_t t = 0; t < termCount; ++t) terms.add(rng() % rowCount, 0.5f * (dist(rng) + 1.0f));
      std::vector<float> start(stride);
      for (float& s : start) s = dist(rng);  // the sum adds to what is there
      std::vector<float> reference = start;
      addWeightedRowsOn(GatherPath::kDefault, terms, previous.data(), stride, reference.data());
      for (std::size_t i = 0; i < stride; ++i) {
        double exact = start[i];
        for (std::size_t t = 0; t < termCount; ++t) exact += double{terms.weights[t]} * previous[terms.rows[t] * stride + i];
        ASSERT_NEAR(reference[i], exact, 1e-5 * (1.0 + static_cast<double>(termCount))) << stride << " " << i;
      }
      for (const GatherPath path : paths) {
        std::vector<float> out = start;
        addWeightedRowsOn(path, terms, previous.data(), stride, out.data());
        EXPECT_TRUE(sameBytes(out, reference)) << gatherPathName(path) << ", stride " << stride << ", " << termCount << " terms";
      }
      std::vector<float> best = start;
      addWeightedRows(terms, previous.data(), stride, best.data());
      EXPECT_TRUE(sameBytes(best, reference)) << stride << " " << termCount;
    }
  }
}

TEST(BounceGather, VertexHitsAreTheirCornersInOrder) {
  std::mt19937 rng(5);
  const std::size_t vertexCount = 30, triangleCount = 20, stride = 75;
  std::vector<std::uint32_t> indices(3 * triangleCount);
  for (std::uint32_t& i : indices) i = static_cast<std::uint32_t>(rng() % vertexCount);
  std::vector<float> previous(vertexCount * stride);
  for (float& p : previous) p = static_cast<float>(rng() % 1000) / 1000.0f;
  std::vector<Hit> hits(40);
  for (Hit& h : hits) {
    h.triangle = static_cast<std::uint32_t>(rng() % triangleCount);
    const std::uint32_t u = rng() % 65536, v = rng() % (65536 - u);  // inside the triangle
    h.u = static_cast<std::uint16_t>(u);
    h.v = static_cast<std::uint16_t>(v);
    h.weight = static_cast<float>(rng() % 1000) / 1000.0f;
  }
  WeightedRows terms;
  std::vector<float> gathered(stride, 0.0f);
  gatherHits(hits, indices.data(), previous.data(), stride, gathered.data(), &terms);
  ASSERT_EQ(terms.rows.size(), 3 * hits.size());
  for (std::size_t h = 0; h < hits.size(); ++h) {
    const float b1 = hits[h].u / 65535.0f, b2 = hits[h].v / 65535.0f;
    const float w[3] = {1.0f - b1 - b2, b1, b2};
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(terms.rows[3 * h + c], indices[3 * hits[h].triangle + c]);
      EXPECT_NEAR(terms.weights[3 * h + c], hits[h].weight * w[c], 1e-6f);
    }
  }
  std::vector<float> expected(stride, 0.0f);
  addWeightedRows(terms, previous.data(), stride, expected.data());
  EXPECT_TRUE(sameBytes(gathered, expected));
}

}  // namespace
}  // namespace prt::bake
