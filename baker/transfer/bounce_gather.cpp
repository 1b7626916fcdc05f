#include "baker/transfer/bounce_gather.h"

#include <cassert>
#include <cstring>

namespace prt::bake {
namespace {

// Rows come from all over the scene: asking for row j + 12's floats (a vertex hit's three
// corners, four hits ahead) while row j is summed took a full dragon scan's bounce from
// 1.9 to 1.6 s (6 and 24 measured no better).
constexpr std::size_t kPrefetchRows = 12;

// The body of every path; each wrapper below compiles it for its own ISA (a callee built for
// the baseline may be inlined into a caller with a wider target). V is a GCC vector of
// floats, N of them a chunk: a chunk of `gathered` is held in registers while every term is
// added to it, because summing straight into memory made each term wait for the previous
// term's store to the same floats (that wait was half the gather's time). The elements left
// over after the last whole chunk are summed one by one in memory. Either way each element
// adds the same products in the same order.
template <typename V, int N>
[[gnu::always_inline]] inline void addRowsBody(const std::size_t* rows, const float* weights, std::size_t count,
                                               const float* previous, std::size_t stride, float* gathered) {
  constexpr std::size_t kLanes = sizeof(V) / sizeof(float), kChunk = kLanes * N;
  std::size_t begin = 0;
  for (; begin + kChunk <= stride; begin += kChunk) {
    V acc[N];
    for (int j = 0; j < N; ++j) std::memcpy(&acc[j], gathered + begin + j * kLanes, sizeof(V));
    for (std::size_t t = 0; t < count; ++t) {
      if (t + kPrefetchRows < count) {
        const char* ahead = reinterpret_cast<const char*>(previous + rows[t + kPrefetchRows] * stride + begin);
        for (std::size_t b = 0; b < kChunk * sizeof(float); b += 64) __builtin_prefetch(ahead + b);
      }
      const float* row = previous + rows[t] * stride + begin;
      const V w = V{} + weights[t];
#pragma GCC unroll 16
      for (int j = 0; j < N; ++j) {
        V r;
        std::memcpy(&r, row + j * kLanes, sizeof(V));
        acc[j] += w * r;
      }
    }
    for (int j = 0; j < N; ++j) std::memcpy(gathered + begin + j * kLanes, &acc[j], sizeof(V));
  }
  if (begin == stride) return;
  for (std::size_t t = 0; t < count; ++t) {
    const float* row = previous + rows[t] * stride;
    for (std::size_t i = begin; i < stride; ++i) gathered[i] += weights[t] * row[i];
  }
}

typedef float Float4 __attribute__((vector_size(16)));
typedef float Float8 __attribute__((vector_size(32)));
typedef float Float16 __attribute__((vector_size(64)));

using AddRowsFn = void (*)(const std::size_t*, const float*, std::size_t, const float*, std::size_t, float*);

void addRowsDefault(const std::size_t* r, const float* w, std::size_t n, const float* p, std::size_t s, float* g) {
  addRowsBody<Float4, 8>(r, w, n, p, s, g);  // 32 floats in 8 of SSE2's 16 registers
}
#if defined(__x86_64__)
__attribute__((target("avx2"))) void addRowsAvx2(const std::size_t* r, const float* w, std::size_t n, const float* p,
                                                 std::size_t s, float* g) {
  addRowsBody<Float8, 8>(r, w, n, p, s, g);  // 64 floats in 8 of AVX2's 16 registers
}
__attribute__((target("avx512f"))) void addRowsAvx512(const std::size_t* r, const float* w, std::size_t n,
                                                      const float* p, std::size_t s, float* g) {
  addRowsBody<Float16, 4>(r, w, n, p, s, g);  // 64 floats in 4 of AVX-512's 32 registers
}
#endif

AddRowsFn addRowsFunction(GatherPath path) {
  switch (path) {
#if defined(__x86_64__)
    case GatherPath::kAvx2: return addRowsAvx2;
    case GatherPath::kAvx512: return addRowsAvx512;
#endif
    default: return addRowsDefault;
  }
}

}  // namespace

const char* gatherPathName(GatherPath path) {
  switch (path) {
    case GatherPath::kAvx2: return "avx2";
    case GatherPath::kAvx512: return "avx512f";
    default: return "default";
  }
}

std::vector<GatherPath> availableGatherPaths() {
  std::vector<GatherPath> paths{GatherPath::kDefault};
#if defined(__x86_64__)
  if (__builtin_cpu_supports("avx2")) paths.push_back(GatherPath::kAvx2);
  if (__builtin_cpu_supports("avx512f")) paths.push_back(GatherPath::kAvx512);
#endif
  return paths;
}

void addWeightedRowsOn(GatherPath path, const WeightedRows& terms, const float* previous, std::size_t stride,
                       float* gathered) {
  assert(terms.rows.size() == terms.weights.size());
  addRowsFunction(path)(terms.rows.data(), terms.weights.data(), terms.rows.size(), previous, stride, gathered);
}

void addWeightedRows(const WeightedRows& terms, const float* previous, std::size_t stride, float* gathered) {
  static const AddRowsFn best = addRowsFunction(availableGatherPaths().back());
  assert(terms.rows.size() == terms.weights.size());
  best(terms.rows.data(), terms.weights.data(), terms.rows.size(), previous, stride, gathered);
}

void gatherHits(std::span<const Hit> hits, const std::uint32_t* indices, const float* previous, std::size_t stride,
                float* gathered, WeightedRows* terms) {
  // Sized once and written in place: growing two vectors term by term cost 15% of a bounce.
  terms->rows.resize(3 * hits.size());
  terms->weights.resize(3 * hits.size());
  std::size_t* rows = terms->rows.data();
  float* weights = terms->weights.data();
  for (std::size_t h = 0; h < hits.size(); ++h) {
    const Hit& hit = hits[h];
    const float b1 = hit.u * (1.0f / 65535.0f), b2 = hit.v * (1.0f / 65535.0f);
    const std::uint32_t* corner = indices + 3 * static_cast<std::size_t>(hit.triangle);
    rows[3 * h] = corner[0];
    rows[3 * h + 1] = corner[1];
    rows[3 * h + 2] = corner[2];
    weights[3 * h] = hit.weight * (1.0f - b1 - b2);
    weights[3 * h + 1] = hit.weight * b1;
    weights[3 * h + 2] = hit.weight * b2;
  }
  addWeightedRows(*terms, previous, stride, gathered);
}

}  // namespace prt::bake
