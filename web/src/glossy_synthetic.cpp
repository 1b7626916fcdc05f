#include "glossy_synthetic.h"

#include <string>

#include "prt/transfer_matrix.h"

namespace prt::web {
namespace {

// SplitMix64: a small, well-mixed deterministic generator (no <random> distribution, whose
// output differs between standard libraries).
struct Rng {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  float uniform() { return static_cast<float>(next() >> 40) / static_cast<float>(1u << 24); }  // [0, 1)
  float symmetric() { return 2.0f * uniform() - 1.0f; }                                       // [-1, 1)
};

}  // namespace

Status makeSyntheticCpcaMatrix(const SyntheticGlossySpec& spec, std::uint32_t vertexCount, CpcaMatrixTransfer* out,
                               std::span<const std::uint8_t> glossy) {
  if (spec.bands < 1 || spec.bands > 8 || (spec.channels != 1 && spec.channels != 3) || spec.clusters < 1 ||
      spec.clusters > 65536 || spec.vectors < 0 || spec.vectors > 64 || (spec.weightBits != 8 && spec.weightBits != 16) ||
      vertexCount == 0 || (spec.packing != MatrixPacking::kFull && spec.packing != MatrixPacking::kSymmetric)) {
    return Status::error(StatusCode::kInvalidArgument, "synthetic glossy pass: bands 1..8, channels 1 or 3, clusters 1..65536, "
                                                       "vectors 0..64, weight bits 8 or 16, at least one vertex");
  }
  if (!glossy.empty() && glossy.size() != vertexCount) {
    return Status::error(StatusCode::kSizeMismatch, "synthetic glossy pass: the glossy mask needs one flag per vertex");
  }
  if (!glossy.empty() && spec.clusters == 65536) return Status::error(StatusCode::kInvalidArgument, "synthetic glossy pass: no room for the zero cluster");
  Rng rng{spec.seed};
  CpcaMatrixTransfer t;
  t.order = t.bands = spec.bands;
  t.channels = spec.channels;
  t.packing = spec.packing;
  t.vertexCount = vertexCount;
  t.clusterCount = static_cast<std::uint32_t>(spec.clusters) + (glossy.empty() ? 0u : 1u);
  t.weightBits = spec.weightBits;
  t.vectors = spec.vectors;
  const std::size_t V = vertexCount, K = t.clusterCount, random = static_cast<std::size_t>(spec.clusters), N = static_cast<std::size_t>(spec.vectors);
  const std::size_t C = static_cast<std::size_t>(spec.channels), n2 = static_cast<std::size_t>(spec.bands * spec.bands);
  const std::size_t entries = matrixEntryCount(spec.bands, spec.packing);
  const int maxLevel = (1 << (spec.weightBits - 1)) - 1;
  t.clusterOf.resize(V);
  for (std::size_t v = 0; v < V; ++v) t.clusterOf[v] = static_cast<std::uint32_t>(rng.next() % random);
  t.steps.resize(K);
  for (std::size_t k = 0; k < K; ++k) t.steps[k] = (0.5f + rng.uniform()) / static_cast<float>(maxLevel);
  t.levels.resize(V * N);
  for (std::int16_t& q : t.levels) q = static_cast<std::int16_t>(static_cast<int>(rng.next() % (2 * maxLevel + 1)) - maxLevel);
  if (!glossy.empty()) {
    for (std::size_t v = 0; v < V; ++v) {
      if (glossy[v]) continue;
      t.clusterOf[v] = static_cast<std::uint32_t>(random);  // the zero cluster
      for (std::size_t j = 0; j < N; ++j) t.levels[v * N + j] = 0;
    }
  }
  t.weights.resize(V * N);
  for (std::size_t v = 0; v < V; ++v)
    for (std::size_t j = 0; j < N; ++j) t.weights[v * N + j] = static_cast<float>(t.levels[v * N + j]) * t.steps[t.clusterOf[v]];
  t.matrices.assign(K * (1 + N) * C * entries, 0.0f);
  for (std::size_t k = 0; k < random; ++k) {  // the zero cluster, if any, stays zero
    for (std::size_t m = 0; m <= N; ++m) {
      for (std::size_t c = 0; c < C; ++c) {
        float* dst = &t.matrices[((k * (1 + N) + m) * C + c) * entries];
        // Mean: a dominant diagonal (a visibility-like projection) plus coupling; basis: smaller.
        for (std::size_t i = 0; i < n2; ++i) {
          for (std::size_t j = 0; j < n2; ++j) {
            if (spec.packing == MatrixPacking::kSymmetric && j > i) continue;
            const float base = m == 0 ? (i == j ? 0.6f + 0.3f * rng.uniform() : 0.15f * rng.symmetric()) : 0.2f * rng.symmetric();
            dst[matrixEntryIndex(i, j, spec.packing)] = base;
          }
        }
      }
    }
  }
  *out = std::move(t);
  return Status::ok();
}

Status expandCpcaMatrix(const CpcaMatrixTransfer& cpca, std::vector<float>* out) {
  const std::size_t V = cpca.vertexCount, K = cpca.clusterCount, C = static_cast<std::size_t>(cpca.channels);
  const std::size_t N = cpca.vectors < 0 ? 0 : static_cast<std::size_t>(cpca.vectors);
  if (cpca.bands < 1 || cpca.bands > 16 || (C != 1 && C != 3)) return Status::error(StatusCode::kInvalidArgument, "expand: bad bands or channels");
  const std::size_t entries = matrixEntryCount(cpca.bands, cpca.packing);
  if (cpca.clusterOf.size() != V || cpca.weights.size() != V * N || cpca.matrices.size() != K * (1 + N) * C * entries) {
    return Status::error(StatusCode::kSizeMismatch, "expand: CPCA matrix arrays disagree with their counts");
  }
  std::vector<float> x(V * C * entries);
  for (std::size_t v = 0; v < V; ++v) {
    const std::size_t k = cpca.clusterOf[v];
    if (k >= K) return Status::error(StatusCode::kCorrupt, "expand: cluster id out of range");
    for (std::size_t c = 0; c < C; ++c) {
      const float* mean = &cpca.matrices[((k * (1 + N)) * C + c) * entries];
      float* dst = &x[(v * C + c) * entries];
      for (std::size_t e = 0; e < entries; ++e) {
        float acc = mean[e];
        for (std::size_t j = 0; j < N; ++j) acc += cpca.weights[v * N + j] * cpca.matrices[((k * (1 + N) + 1 + j) * C + c) * entries + e];
        dst[e] = acc;
      }
    }
  }
  *out = std::move(x);
  return Status::ok();
}

}  // namespace prt::web
