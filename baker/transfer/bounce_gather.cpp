#include "baker/transfer/bounce_gather.h"

#include <cstring>

namespace prt::bake {
namespace {

// The corner weights of a hit: hit.weight times (1 - b1 - b2, b1, b2).
[[gnu::always_inline]] inline void cornerWeights(const Hit& hit, float w[3]) {
  const float b1 = hit.u * (1.0f / 65535.0f), b2 = hit.v * (1.0f / 65535.0f);
  w[0] = hit.weight * (1.0f - b1 - b2);
  w[1] = hit.weight * b1;
  w[2] = hit.weight * b2;
}

// The body of every path; each wrapper below compiles it for its own ISA (a callee built for
// the baseline may be inlined into a caller with a wider target). V is a GCC vector of
// floats, N of them a chunk: a chunk of `gathered` is held in registers while every hit is
// added to it, because summing straight into memory made each corner wait for the previous
// corner's store to the same floats (that wait was half the gather's time). The elements
// left over after the last whole chunk are summed one by one in memory. Either way each
// element adds the same products in the same order.
// Rows are fetched from all over the scene: asking for hit h + 4's rows while hit h is summed
// took a full dragon scan's bounce from 1.9 to 1.6 s (2 and 8 measured no better).
constexpr std::size_t kPrefetchHits = 4;

template <typename V, int N>
[[gnu::always_inline]] inline void gatherBody(const Hit* hits, std::size_t count, const std::uint32_t* indices,
                                              const float* previous, std::size_t stride, float* gathered) {
  constexpr std::size_t kLanes = sizeof(V) / sizeof(float), kChunk = kLanes * N;
  std::size_t begin = 0;
  for (; begin + kChunk <= stride; begin += kChunk) {
    V acc[N];
    for (int j = 0; j < N; ++j) std::memcpy(&acc[j], gathered + begin + j * kLanes, sizeof(V));
    for (std::size_t h = 0; h < count; ++h) {
      if (h + kPrefetchHits < count) {
        const std::size_t t = 3 * static_cast<std::size_t>(hits[h + kPrefetchHits].triangle);
        for (int corner = 0; corner < 3; ++corner) {
          const char* row = reinterpret_cast<const char*>(previous + static_cast<std::size_t>(indices[t + corner]) * stride + begin);
          for (std::size_t b = 0; b < kChunk * sizeof(float); b += 64) __builtin_prefetch(row + b);
        }
      }
      float w[3];
      cornerWeights(hits[h], w);
      for (int corner = 0; corner < 3; ++corner) {
        const float* row =
            previous + static_cast<std::size_t>(indices[3 * static_cast<std::size_t>(hits[h].triangle) + corner]) * stride + begin;
        const V wc = V{} + w[corner];
#pragma GCC unroll 16
        for (int j = 0; j < N; ++j) {
          V r;
          std::memcpy(&r, row + j * kLanes, sizeof(V));
          acc[j] += wc * r;
        }
      }
    }
    for (int j = 0; j < N; ++j) std::memcpy(gathered + begin + j * kLanes, &acc[j], sizeof(V));
  }
  if (begin == stride) return;
  for (std::size_t h = 0; h < count; ++h) {
    float w[3];
    cornerWeights(hits[h], w);
    for (int corner = 0; corner < 3; ++corner) {
      const float* row = previous + static_cast<std::size_t>(indices[3 * static_cast<std::size_t>(hits[h].triangle) + corner]) * stride;
      for (std::size_t i = begin; i < stride; ++i) gathered[i] += w[corner] * row[i];
    }
  }
}

typedef float Float4 __attribute__((vector_size(16)));
typedef float Float8 __attribute__((vector_size(32)));
typedef float Float16 __attribute__((vector_size(64)));

using GatherFn = void (*)(const Hit*, std::size_t, const std::uint32_t*, const float*, std::size_t, float*);

void gatherDefault(const Hit* h, std::size_t n, const std::uint32_t* x, const float* p, std::size_t s, float* g) {
  gatherBody<Float4, 8>(h, n, x, p, s, g);  // 32 floats in 8 of SSE2's 16 registers
}
#if defined(__x86_64__)
__attribute__((target("avx2"))) void gatherAvx2(const Hit* h, std::size_t n, const std::uint32_t* x, const float* p,
                                                std::size_t s, float* g) {
  gatherBody<Float8, 8>(h, n, x, p, s, g);  // 64 floats in 8 of AVX2's 16 registers
}
__attribute__((target("avx512f"))) void gatherAvx512(const Hit* h, std::size_t n, const std::uint32_t* x,
                                                     const float* p, std::size_t s, float* g) {
  gatherBody<Float16, 4>(h, n, x, p, s, g);  // 64 floats in 4 of AVX-512's 32 registers
}
#endif

GatherFn gatherFunction(GatherPath path) {
  switch (path) {
#if defined(__x86_64__)
    case GatherPath::kAvx2: return gatherAvx2;
    case GatherPath::kAvx512: return gatherAvx512;
#endif
    default: return gatherDefault;
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

void gatherHitsOn(GatherPath path, std::span<const Hit> hits, const std::uint32_t* indices, const float* previous,
                  std::size_t stride, float* gathered) {
  gatherFunction(path)(hits.data(), hits.size(), indices, previous, stride, gathered);
}

void gatherHits(std::span<const Hit> hits, const std::uint32_t* indices, const float* previous, std::size_t stride,
                float* gathered) {
  static const GatherFn best = gatherFunction(availableGatherPaths().back());
  best(hits.data(), hits.size(), indices, previous, stride, gathered);
}

}  // namespace prt::bake
