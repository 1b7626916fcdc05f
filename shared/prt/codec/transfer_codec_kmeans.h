// Deterministic k-means for the CPCA encoder: k-means++ seeding (Arthur & Vassilvitskii
// 2007) from a fixed seed, Lloyd iterations on an evenly strided sample of at most
// `maxTrainingPoints` points (until at most 0.1% of them change cluster), then every point
// assigned to its nearest centre.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace prt::transfer_codec {

struct KMeansOptions {
  int clusters = 1;                        // wanted; at most the number of distinct points survive
  std::uint64_t seed = 1;
  std::size_t maxTrainingPoints = 16384;   // Lloyd runs on this many points at most
  int maxIterations = 25;
};

struct KMeansResult {
  int clusters = 0;                    // non-empty clusters, numbered 0..clusters-1
  std::vector<std::uint32_t> assignment;  // per point
};

// Clusters `count` points of `dims` floats each (`points` is [point][dim]) by squared
// Euclidean distance. Empty clusters are dropped and the rest renumbered in order of
// their first point, so the result depends only on the input and the options.
KMeansResult kMeans(std::span<const float> points, std::size_t count, int dims, const KMeansOptions& options);

// A small deterministic generator (SplitMix64) so results match on every platform.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  double nextDouble();  // uniform in [0, 1)
 private:
  std::uint64_t state_;
};

}  // namespace prt::transfer_codec
