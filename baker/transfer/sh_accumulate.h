// The SH projection of the direct pass, out[i] = sum_k weights[k] basis[i][k], vectorised
// for the machine it runs on (AVX2, else SSE2) and the same bits on every path: the sum
// runs in one fixed order that each path implements exactly (below), with multiplies and
// adds rounded separately (no FMA contraction: this file builds with -ffp-contract=off).
// Private to prt_transfer.
#pragma once

#include <cstddef>
#include <vector>

namespace prt::bake {

// The fixed order: 32 lanes, lane l summing weights[k] * basis[i][k] for k = l mod 32 in
// ascending k (the samples zero-padded to a multiple of 32), then the lanes folded in
// halves, lane l += lane l + 16, then + 8, + 4, + 2, + 1.
inline constexpr std::size_t kAccumulateLanes = 32;

// out[i] for i in [0, n2): basis is [coefficient][sample] with `count` samples per row;
// weights has `count` entries. Uses the fastest path this CPU has (chosen once).
void projectWeights(int n2, std::size_t count, const float* weights, const float* basis, float* out);

// The implementations, for tests and benchmarks. kScalar is the order written as plain C++.
enum class SimdPath { kScalar, kSse2, kAvx2 };
const char* simdPathName(SimdPath path);
// The paths this CPU runs, kScalar first; the last is the one projectWeights uses.
std::vector<SimdPath> availableSimdPaths();
// projectWeights on `path` (which must be available).
void projectWeightsOn(SimdPath path, int n2, std::size_t count, const float* weights, const float* basis, float* out);

}  // namespace prt::bake
