#include "baker/transfer/sh_accumulate.h"

#include <cassert>
#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define PRT_X86_SIMD 1
#endif

namespace prt::bake {
namespace {

constexpr std::size_t kLanes = kAccumulateLanes;

// The last, partial chunk of a row, zero-padded, so every path adds the same zeros.
struct PaddedTail {
  float w[kLanes], b[kLanes];
  PaddedTail(const float* weights, const float* row, std::size_t n) {
    std::memset(w, 0, sizeof w);
    std::memset(b, 0, sizeof b);
    std::memcpy(w, weights, n * sizeof(float));
    std::memcpy(b, row, n * sizeof(float));
  }
};

float rowScalar(std::size_t count, const float* weights, const float* row) {
  float lane[kLanes] = {};
  const std::size_t full = count / kLanes * kLanes;
  for (std::size_t k = 0; k < full; k += kLanes) {
    for (std::size_t l = 0; l < kLanes; ++l) lane[l] += weights[k + l] * row[k + l];
  }
  if (full < count) {
    const PaddedTail t(weights + full, row + full, count - full);
    for (std::size_t l = 0; l < kLanes; ++l) lane[l] += t.w[l] * t.b[l];
  }
  for (std::size_t half = kLanes / 2; half > 0; half /= 2) {
    for (std::size_t l = 0; l < half; ++l) lane[l] += lane[l + half];
  }
  return lane[0];
}

#ifdef PRT_X86_SIMD
// acc[j] holds lanes 4j .. 4j+3.
float rowSse2(std::size_t count, const float* weights, const float* row) {
  __m128 acc[8];
  for (__m128& a : acc) a = _mm_setzero_ps();
  auto chunk = [&acc](const float* w, const float* b) {
    for (int j = 0; j < 8; ++j) acc[j] = _mm_add_ps(acc[j], _mm_mul_ps(_mm_loadu_ps(w + 4 * j), _mm_loadu_ps(b + 4 * j)));
  };
  const std::size_t full = count / kLanes * kLanes;
  for (std::size_t k = 0; k < full; k += kLanes) chunk(weights + k, row + k);
  if (full < count) {
    const PaddedTail t(weights + full, row + full, count - full);
    chunk(t.w, t.b);
  }
  for (int j = 0; j < 4; ++j) acc[j] = _mm_add_ps(acc[j], acc[j + 4]);  // + 16
  for (int j = 0; j < 2; ++j) acc[j] = _mm_add_ps(acc[j], acc[j + 2]);  // + 8
  __m128 x = _mm_add_ps(acc[0], acc[1]);                                 // + 4
  x = _mm_add_ps(x, _mm_movehl_ps(x, x));                                 // + 2
  x = _mm_add_ss(x, _mm_shuffle_ps(x, x, 1));                             // + 1
  return _mm_cvtss_f32(x);
}

// acc[j] holds lanes 8j .. 8j+7.
__attribute__((target("avx2"))) float rowAvx2(std::size_t count, const float* weights, const float* row) {
  __m256 acc[4];
  for (__m256& a : acc) a = _mm256_setzero_ps();
  auto chunk = [&acc](const float* w, const float* b) __attribute__((target("avx2"))) {
    for (int j = 0; j < 4; ++j) {
      acc[j] = _mm256_add_ps(acc[j], _mm256_mul_ps(_mm256_loadu_ps(w + 8 * j), _mm256_loadu_ps(b + 8 * j)));
    }
  };
  const std::size_t full = count / kLanes * kLanes;
  for (std::size_t k = 0; k < full; k += kLanes) chunk(weights + k, row + k);
  if (full < count) {
    const PaddedTail t(weights + full, row + full, count - full);
    chunk(t.w, t.b);
  }
  acc[0] = _mm256_add_ps(acc[0], acc[2]);  // + 16
  acc[1] = _mm256_add_ps(acc[1], acc[3]);
  const __m256 y = _mm256_add_ps(acc[0], acc[1]);  // + 8
  __m128 x = _mm_add_ps(_mm256_castps256_ps128(y), _mm256_extractf128_ps(y, 1));  // + 4
  x = _mm_add_ps(x, _mm_movehl_ps(x, x));                                         // + 2
  x = _mm_add_ss(x, _mm_shuffle_ps(x, x, 1));                                     // + 1
  return _mm_cvtss_f32(x);
}
#endif

using RowFn = float (*)(std::size_t, const float*, const float*);

RowFn rowFunction(SimdPath path) {
  switch (path) {
#ifdef PRT_X86_SIMD
    case SimdPath::kSse2: return rowSse2;
    case SimdPath::kAvx2: return rowAvx2;
#endif
    default: return rowScalar;
  }
}

void projectRows(RowFn row, int n2, std::size_t count, const float* weights, const float* basis, float* out) {
  for (int i = 0; i < n2; ++i) out[i] = row(count, weights, basis + static_cast<std::size_t>(i) * count);
}

}  // namespace

const char* simdPathName(SimdPath path) {
  switch (path) {
    case SimdPath::kSse2: return "sse2";
    case SimdPath::kAvx2: return "avx2";
    default: return "scalar";
  }
}

std::vector<SimdPath> availableSimdPaths() {
  std::vector<SimdPath> paths{SimdPath::kScalar};
#ifdef PRT_X86_SIMD
  paths.push_back(SimdPath::kSse2);  // x86-64's baseline
  if (__builtin_cpu_supports("avx2")) paths.push_back(SimdPath::kAvx2);
#endif
  return paths;
}

void projectWeightsOn(SimdPath path, int n2, std::size_t count, const float* weights, const float* basis, float* out) {
  projectRows(rowFunction(path), n2, count, weights, basis, out);
}

void projectWeights(int n2, std::size_t count, const float* weights, const float* basis, float* out) {
  static const RowFn best = rowFunction(availableSimdPaths().back());
  projectRows(best, n2, count, weights, basis, out);
}

}  // namespace prt::bake
