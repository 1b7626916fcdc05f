#include "transfer_codec_kmeans.h"

#include <algorithm>
#include <limits>

namespace prt::transfer_codec {

std::uint64_t SplitMix64::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

double SplitMix64::nextDouble() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

namespace {

// Centres stored transposed, [dim][cluster], so the distance loop over clusters vectorises
// without a horizontal reduction (and so without changing the summation order).
struct Centres {
  int k = 0, dims = 0;
  std::vector<float> t;  // dims * k
  void set(int cluster, const float* x) {
    for (int d = 0; d < dims; ++d) t[static_cast<std::size_t>(d) * static_cast<std::size_t>(k) + static_cast<std::size_t>(cluster)] = x[d];
  }
};

// Index of the nearest centre to x (first on ties) and its squared distance.
int nearest(const Centres& c, const float* x, std::vector<float>& dist, float* best) {
  std::fill(dist.begin(), dist.end(), 0.0f);
  const std::size_t k = static_cast<std::size_t>(c.k);
  for (int d = 0; d < c.dims; ++d) {
    const float xd = x[d];
    const float* row = c.t.data() + static_cast<std::size_t>(d) * k;
    for (std::size_t j = 0; j < k; ++j) {
      const float diff = xd - row[j];
      dist[j] += diff * diff;
    }
  }
  int arg = 0;
  for (std::size_t j = 1; j < k; ++j) {
    if (dist[j] < dist[static_cast<std::size_t>(arg)]) arg = static_cast<int>(j);
  }
  *best = dist[static_cast<std::size_t>(arg)];
  return arg;
}

float squaredDistance(const float* a, const float* b, int dims) {
  float s = 0.0f;
  for (int d = 0; d < dims; ++d) {
    const float diff = a[d] - b[d];
    s += diff * diff;
  }
  return s;
}

}  // namespace

KMeansResult kMeans(std::span<const float> points, std::size_t count, int dims, const KMeansOptions& o) {
  const std::size_t D = static_cast<std::size_t>(dims);
  auto point = [&](std::size_t i) { return points.data() + i * D; };

  // Evenly strided training sample.
  std::vector<std::size_t> sample;
  const std::size_t n = std::min(count, std::max<std::size_t>(o.maxTrainingPoints, 1));
  sample.reserve(n);
  for (std::size_t i = 0; i < n; ++i) sample.push_back(static_cast<std::size_t>((static_cast<unsigned long long>(i) * count) / n));
  const int k = std::max(1, std::min<int>(o.clusters, static_cast<int>(n)));

  // k-means++ seeding: each next centre drawn with probability proportional to D^2.
  Centres c;
  c.k = k;
  c.dims = dims;
  c.t.assign(D * static_cast<std::size_t>(k), 0.0f);
  SplitMix64 rng(o.seed);
  std::vector<double> d2(n, std::numeric_limits<double>::infinity());
  std::size_t chosen = static_cast<std::size_t>(rng.next() % n);
  for (int j = 0; j < k; ++j) {
    c.set(j, point(sample[chosen]));
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      d2[i] = std::min(d2[i], static_cast<double>(squaredDistance(point(sample[i]), point(sample[chosen]), dims)));
      total += d2[i];
    }
    if (j + 1 == k) break;
    if (total <= 0.0) {
      chosen = static_cast<std::size_t>(rng.next() % n);  // all points coincide with centres: duplicates die below
      continue;
    }
    const double target = rng.nextDouble() * total;
    double acc = 0.0;
    chosen = n - 1;
    for (std::size_t i = 0; i < n; ++i) {
      acc += d2[i];
      if (acc > target && d2[i] > 0.0) {
        chosen = i;
        break;
      }
    }
  }

  // Lloyd iterations on the sample.
  std::vector<float> dist(static_cast<std::size_t>(k));
  std::vector<int> label(n, -1);
  std::vector<float> labelDist(n, 0.0f);
  std::vector<double> sums(D * static_cast<std::size_t>(k));
  std::vector<std::size_t> sizes(static_cast<std::size_t>(k));
  std::vector<float> centre(D);
  for (int iter = 0; iter < o.maxIterations; ++iter) {
    std::size_t changed = 0;
    for (std::size_t i = 0; i < n; ++i) {
      float best = 0.0f;
      const int a = nearest(c, point(sample[i]), dist, &best);
      if (a != label[i]) ++changed;
      label[i] = a;
      labelDist[i] = best;
    }
    // Converged enough: the last few points moving changes the centres by little, and
    // each further iteration costs as much as the first.
    if (changed <= n / 1000) break;
    std::fill(sums.begin(), sums.end(), 0.0);
    std::fill(sizes.begin(), sizes.end(), 0);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t a = static_cast<std::size_t>(label[i]);
      ++sizes[a];
      const float* x = point(sample[i]);
      for (std::size_t d = 0; d < D; ++d) sums[a * D + d] += x[d];
    }
    for (int j = 0; j < k; ++j) {
      const std::size_t js = static_cast<std::size_t>(j);
      if (sizes[js] == 0) {
        // Re-seed an empty cluster at the sample point farthest from its centre.
        std::size_t far = 0;
        for (std::size_t i = 1; i < n; ++i) {
          if (labelDist[i] > labelDist[far]) far = i;
        }
        labelDist[far] = 0.0f;
        c.set(j, point(sample[far]));
        continue;
      }
      for (std::size_t d = 0; d < D; ++d) centre[d] = static_cast<float>(sums[js * D + d] / static_cast<double>(sizes[js]));
      c.set(j, centre.data());
    }
  }

  // Every point to its nearest centre; drop empty clusters, number by first appearance.
  KMeansResult r;
  r.assignment.resize(count);
  std::vector<int> renumber(static_cast<std::size_t>(k), -1);
  for (std::size_t i = 0; i < count; ++i) {
    float best = 0.0f;
    const std::size_t a = static_cast<std::size_t>(nearest(c, point(i), dist, &best));
    if (renumber[a] < 0) renumber[a] = r.clusters++;
    r.assignment[i] = static_cast<std::uint32_t>(renumber[a]);
  }
  return r;
}

}  // namespace prt::transfer_codec
