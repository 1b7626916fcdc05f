// The matrix CPCA encoder (docs/transfer-codec.md "Matrices"; Sloan et al. 2003 §4.1): each
// vertex's whole matrix transfer (channels x packed entries, D values) is one point.
//
// Scale: D reaches 3 * 625 = 1875 at order 5 (RGB, full), so no D x D covariance is formed.
//  1. A global randomized PCA (Halko, Martinsson & Tropp 2011: a Gaussian sketch, one power
//     iteration) gives a kSketch-dimensional subspace; k-means++ runs on the vertices'
//     coordinates in it.
//  2. Per cluster, the same randomized subspace iteration on the members (centred on their
//     float mean) gives kMaxVectors principal matrices and the members' weights; a cluster
//     with fewer members than the sketch is captured exactly (its rows span the subspace).
//  3. For each basis count N' and weight step delta the error is known in weight space
//     (dropped eigenvalues + quantisation error of the kept weights, + the rounding of 8-bit
//     basis entries when settings.cpcaBasisBits is 8) and the size after an entropy coder is
//     estimated (tables raw, streams by order-0 entropy per byte plane).
// Each pass over the data is an axpy over the sketch width, so it vectorises without
// reassociation (-ffp-contract=off holds); temporary memory is O(V * kSketch + K * kMaxVectors * D).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "transfer_codec_basis8.h"
#include "transfer_codec_eigen.h"
#include "prt/half_float.h"
#include "transfer_codec_kmeans.h"
#include "transfer_codec_matrix.h"
#include "transfer_codec_streams.h"

namespace prt::transfer_codec {
namespace {

constexpr int kMaxVectors = 32;      // N' <= this
constexpr int kOversample = 8;       // sketch columns beyond kMaxVectors
constexpr int kSketch = kMaxVectors + kOversample;
constexpr double kEstimateMargin = 0.97;  // estimates aim a little under the target
constexpr int kDeltaSteps = 20;      // deltas tried: maxWeight * 2^-i, i = 1..kDeltaSteps, and 0
constexpr int kVerifyRetries = 12;
// Above this many vertices the cluster count is searched on an evenly strided sample of
// this size (the fits cost O(V D kSketch) each), and only the winner is fitted on all of
// them; the global sketch is computed on the sample too, then every vertex projected once.
constexpr std::size_t kSearchVertices = 4096;
// The sample search keeps at least this many members per cluster on average, so that a
// per-cluster PCA does not look better than it is by fitting few points exactly.
constexpr std::size_t kMinSampleMembers = 32;

// Unit Gaussian numbers by Box-Muller from SplitMix64 (deterministic on every platform).
void gaussian(SplitMix64& rng, std::vector<float>& out) {
  for (std::size_t i = 0; i < out.size(); i += 2) {
    const double u1 = 1.0 - rng.nextDouble(), u2 = rng.nextDouble();
    const double r = std::sqrt(-2.0 * std::log(u1)), a = 6.283185307179586 * u2;
    out[i] = static_cast<float>(r * std::cos(a));
    if (i + 1 < out.size()) out[i + 1] = static_cast<float>(r * std::sin(a));
  }
}

// Orthonormalises the columns of `m` (rows x cols, row-major) by modified Gram-Schmidt, twice
// (in double), dropping columns that are (numerically) dependent. Returns the kept count;
// the kept columns are packed to the left (rows x kept, row-major).
int orthonormalColumns(std::vector<float>& m, std::size_t rows, int cols) {
  std::vector<double> c(static_cast<std::size_t>(cols) * rows);  // column-major copy
  for (std::size_t r = 0; r < rows; ++r)
    for (int j = 0; j < cols; ++j) c[static_cast<std::size_t>(j) * rows + r] = m[r * static_cast<std::size_t>(cols) + static_cast<std::size_t>(j)];
  double largest = 0.0;
  for (int j = 0; j < cols; ++j) {
    double n = 0.0;
    for (std::size_t r = 0; r < rows; ++r) n += c[static_cast<std::size_t>(j) * rows + r] * c[static_cast<std::size_t>(j) * rows + r];
    largest = std::max(largest, std::sqrt(n));
  }
  int kept = 0;
  for (int j = 0; j < cols; ++j) {
    double* col = &c[static_cast<std::size_t>(j) * rows];
    double before = 0.0;
    for (std::size_t r = 0; r < rows; ++r) before += col[r] * col[r];
    for (int pass = 0; pass < 2; ++pass) {
      for (int i = 0; i < kept; ++i) {
        const double* q = &c[static_cast<std::size_t>(i) * rows];
        double dot = 0.0;
        for (std::size_t r = 0; r < rows; ++r) dot += q[r] * col[r];
        for (std::size_t r = 0; r < rows; ++r) col[r] -= dot * q[r];
      }
    }
    double n = 0.0;
    for (std::size_t r = 0; r < rows; ++r) n += col[r] * col[r];
    n = std::sqrt(n);
    // Dependent: what is left is rounding noise of the column or of the largest one.
    if (!(n > 1e-6 * std::sqrt(before)) || !(n > 1e-9 * largest) || n == 0.0) continue;
    double* dst = &c[static_cast<std::size_t>(kept) * rows];
    for (std::size_t r = 0; r < rows; ++r) dst[r] = col[r] / n;
    ++kept;
  }
  m.assign(rows * static_cast<std::size_t>(kept), 0.0f);
  for (std::size_t r = 0; r < rows; ++r)
    for (int j = 0; j < kept; ++j) m[r * static_cast<std::size_t>(kept) + static_cast<std::size_t>(j)] = static_cast<float>(c[static_cast<std::size_t>(j) * rows + r]);
  return kept;
}

// The rows `members` of X (each D floats) minus `mean`, fed one at a time to `f(i, row)`.
template <typename F>
void forCentred(std::span<const float> x, std::size_t D, std::span<const std::uint32_t> members, const float* mean,
                std::vector<float>& row, F&& f) {
  row.resize(D);
  for (std::size_t i = 0; i < members.size(); ++i) {
    const float* src = x.data() + static_cast<std::size_t>(members[i]) * D;
    for (std::size_t d = 0; d < D; ++d) row[d] = src[d] - mean[d];
    f(i, row.data());
  }
}

// y (l) = row (D) * M (D x l, row-major): an axpy per d.
void rowTimes(const float* row, const float* m, std::size_t D, std::size_t l, float* y) {
  std::fill(y, y + l, 0.0f);
  for (std::size_t d = 0; d < D; ++d) {
    const float a = row[d];
    const float* mr = m + d * l;
    for (std::size_t t = 0; t < l; ++t) y[t] += a * mr[t];
  }
}

struct Subspace {
  int dims = 0;              // kept orthonormal columns
  std::vector<float> q;      // D x dims, row-major: the subspace basis
  std::vector<float> coords; // members x dims: the members' coordinates in it
};

// Randomized range finder with one power iteration over the centred members (module comment).
Subspace sketch(std::span<const float> x, std::size_t D, std::span<const std::uint32_t> members, const float* mean,
                int width, std::uint64_t seed) {
  const std::size_t n = members.size();
  const std::size_t l = static_cast<std::size_t>(std::min<std::size_t>(static_cast<std::size_t>(width), D));
  std::vector<float> omega(D * l), row;
  SplitMix64 rng(seed);
  gaussian(rng, omega);
  std::vector<float> y(n * l);
  forCentred(x, D, members, mean, row, [&](std::size_t i, const float* r) { rowTimes(r, omega.data(), D, l, &y[i * l]); });
  const int ly = orthonormalColumns(y, n, static_cast<int>(l));
  Subspace s;
  if (ly == 0) return s;  // every member equals the mean
  const std::size_t L = static_cast<std::size_t>(ly);
  std::vector<float> z(D * L, 0.0f);
  forCentred(x, D, members, mean, row, [&](std::size_t i, const float* r) {
    const float* yi = &y[i * L];
    for (std::size_t d = 0; d < D; ++d) {
      const float a = r[d];
      float* zr = &z[d * L];
      for (std::size_t t = 0; t < L; ++t) zr[t] += a * yi[t];
    }
  });
  s.dims = orthonormalColumns(z, D, ly);
  s.q = std::move(z);
  const std::size_t K = static_cast<std::size_t>(s.dims);
  s.coords.assign(n * K, 0.0f);
  if (K > 0) {
    forCentred(x, D, members, mean, row, [&](std::size_t i, const float* r) { rowTimes(r, s.q.data(), D, K, &s.coords[i * K]); });
  }
  return s;
}

struct ClusterFit {
  std::vector<float> mean;        // D
  int vectors = 0;                // principal matrices found (<= kMaxVectors)
  std::vector<float> basis;       // vectors x D, unit, descending energy
  std::vector<double> energy;     // vectors: sum over members of weight^2
  double centredEnergy = 0.0;     // sum over members of |x - mean|^2
};

struct MatrixFit {
  int clusters = 0;
  std::vector<std::uint32_t> clusterOf;
  std::vector<ClusterFit> fits;
  std::vector<float> weights;  // V x kMaxVectors (0 beyond a cluster's vectors)
  double energy = 0.0;         // sum x^2
};

MatrixFit fitMatrixCpca(std::span<const float> x, std::size_t V, std::size_t D, int clusters, std::uint64_t seed,
                        std::span<const float> points, int pointDims, double energy) {
  MatrixFit fit;
  fit.energy = energy;
  KMeansOptions o;
  o.clusters = clusters;
  o.seed = seed;
  KMeansResult km = kMeans(points, V, pointDims, o);
  fit.clusters = km.clusters;
  fit.clusterOf = std::move(km.assignment);
  std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(fit.clusters));
  for (std::size_t v = 0; v < V; ++v) members[fit.clusterOf[v]].push_back(static_cast<std::uint32_t>(v));
  fit.fits.resize(static_cast<std::size_t>(fit.clusters));
  fit.weights.assign(V * kMaxVectors, 0.0f);
  std::vector<float> row;
  for (std::size_t k = 0; k < members.size(); ++k) {
    ClusterFit& cf = fit.fits[k];
    const auto& mem = members[k];
    std::vector<double> mean(D, 0.0);
    for (std::uint32_t v : mem) {
      const float* src = x.data() + static_cast<std::size_t>(v) * D;
      for (std::size_t d = 0; d < D; ++d) mean[d] += src[d];
    }
    cf.mean.resize(D);
    for (std::size_t d = 0; d < D; ++d) cf.mean[d] = static_cast<float>(mean[d] / static_cast<double>(mem.size()));
    forCentred(x, D, mem, cf.mean.data(), row, [&](std::size_t, const float* r) {
      for (std::size_t d = 0; d < D; ++d) cf.centredEnergy += static_cast<double>(r[d]) * r[d];
    });
    const Subspace s = sketch(x, D, mem, cf.mean.data(), kSketch, seed + 0x9e37u * (k + 1));
    if (s.dims == 0) continue;
    // Rayleigh-Ritz in the subspace: eigenvectors of coords^T coords.
    const std::size_t L = static_cast<std::size_t>(s.dims), n = mem.size();
    std::vector<double> g(L * L, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const float* c = &s.coords[i * L];
      for (std::size_t a = 0; a < L; ++a)
        for (std::size_t b = 0; b <= a; ++b) g[a * L + b] += static_cast<double>(c[a]) * c[b];
    }
    for (std::size_t a = 0; a < L; ++a)
      for (std::size_t b = 0; b < a; ++b) g[b * L + a] = g[a * L + b];
    const SymmetricEigen eig = symmetricEigen(static_cast<int>(L), g);
    int kept = 0;
    while (kept < kMaxVectors && static_cast<std::size_t>(kept) < L && eig.values[static_cast<std::size_t>(kept)] > 0.0) ++kept;
    cf.vectors = kept;
    cf.basis.assign(static_cast<std::size_t>(kept) * D, 0.0f);
    cf.energy.assign(static_cast<std::size_t>(kept), 0.0);
    for (int j = 0; j < kept; ++j) {
      const double* u = &eig.vectors[static_cast<std::size_t>(j) * L];
      float* b = &cf.basis[static_cast<std::size_t>(j) * D];
      for (std::size_t d = 0; d < D; ++d) {
        double acc = 0.0;
        for (std::size_t t = 0; t < L; ++t) acc += static_cast<double>(s.q[d * L + t]) * u[t];
        b[d] = static_cast<float>(acc);
      }
      for (std::size_t i = 0; i < n; ++i) {
        double w = 0.0;
        for (std::size_t t = 0; t < L; ++t) w += static_cast<double>(s.coords[i * L + t]) * u[t];
        fit.weights[static_cast<std::size_t>(mem[i]) * kMaxVectors + static_cast<std::size_t>(j)] = static_cast<float>(w);
        cf.energy[static_cast<std::size_t>(j)] += w * w;
      }
    }
  }
  return fit;
}

// Step of cluster k: delta, or more where its weights' range needs it to fit Q levels.
float clusterStep(double delta, double range, int levels) {
  const double wanted = std::max(delta, range / levels);
  if (wanted == 0.0) return 0.0f;
  float step = std::max(static_cast<float>(wanted), std::numeric_limits<float>::min());
  while (static_cast<double>(step) * levels < range) step = std::nextafter(step, 2.0f * step + 1.0f);
  return step;
}

std::int32_t quantise(double w, float step, int levels) {
  if (step <= 0.0f) return 0;
  const double q = std::nearbyint(w / static_cast<double>(step));
  return static_cast<std::int32_t>(std::clamp(q, -static_cast<double>(levels), static_cast<double>(levels)));
}

struct Quantised {
  std::vector<float> steps;           // per cluster
  std::vector<std::int32_t> levels;   // [vector j][vertex], kMaxVectors streams
};

Quantised quantiseWeights(const MatrixFit& fit, std::size_t V, double delta, int levelsMax) {
  Quantised q;
  std::vector<double> range(static_cast<std::size_t>(fit.clusters), 0.0);
  for (std::size_t v = 0; v < V; ++v)
    for (int j = 0; j < kMaxVectors; ++j)
      range[fit.clusterOf[v]] = std::max(range[fit.clusterOf[v]], std::fabs(static_cast<double>(fit.weights[v * kMaxVectors + static_cast<std::size_t>(j)])));
  q.steps.resize(range.size());
  for (std::size_t k = 0; k < range.size(); ++k) q.steps[k] = clusterStep(delta, range[k], levelsMax);
  q.levels.resize(V * kMaxVectors);
  for (std::size_t v = 0; v < V; ++v)
    for (std::size_t j = 0; j < kMaxVectors; ++j)
      q.levels[j * V + v] = quantise(fit.weights[v * kMaxVectors + j], q.steps[fit.clusterOf[v]], levelsMax);
  return q;
}

struct Choice {
  double bytes = INFINITY;
  int vectors = 0;
  double delta = 0.0;
};

// The entries of basis matrix j of `cf` in shell `band` as they are stored: divided by the
// entry weights (if any) in float, exactly as encodeMatrixCpca does before writing.
std::vector<float> storedShell(const ClusterFit& cf, std::size_t j, std::span<const float> entryWeight, int order, int band,
                               MatrixPacking packing, int channels) {
  const std::size_t E = matrixEntryCount(order, packing), C = static_cast<std::size_t>(channels), D = C * E;
  const std::size_t first = matrixEntryCount(band, packing), S = static_cast<std::size_t>(shellEntries(band, packing));
  std::vector<float> u(C * S);
  for (std::size_t c = 0; c < C; ++c)
    for (std::size_t e = 0; e < S; ++e) {
      const std::size_t d = c * E + first + e;
      u[c * S + e] = entryWeight.empty() ? cf.basis[j * D + d] : cf.basis[j * D + d] / entryWeight[d];
    }
  return u;
}

// Per basis matrix j of `cf`: the squared norm, in the fitted (weighted) space, of the
// rounding error of its 8-bit storage (a scale per shell). The members' weights on basis j
// have energy lambda_j and are uncorrelated with those on the other basis matrices
// (Rayleigh-Ritz), so storing B_j as B_j + dB_j adds lambda_j |dB_j|^2 to the cluster's error.
std::vector<double> basis8Errors(const ClusterFit& cf, std::span<const float> entryWeight, int order, MatrixPacking packing,
                                 int channels) {
  const std::size_t E = matrixEntryCount(order, packing), C = static_cast<std::size_t>(channels);
  std::vector<double> err(static_cast<std::size_t>(cf.vectors), 0.0);
  for (std::size_t j = 0; j < err.size(); ++j) {
    for (int b = 0; b < order; ++b) {
      const std::vector<float> u = storedShell(cf, j, entryWeight, order, b, packing, channels);
      const float scale = basisScale(u);
      const std::size_t first = matrixEntryCount(b, packing), S = u.size() / C;
      for (std::size_t i = 0; i < u.size(); ++i) {
        const double w = entryWeight.empty() ? 1.0 : static_cast<double>(entryWeight[(i / S) * E + first + i % S]);
        const double e = (static_cast<double>(basisValue(basisLevel(u[i], scale), scale)) - u[i]) * w;
        err[j] += e * e;
      }
    }
  }
  return err;
}

// Best (N', delta) of one fit: smallest estimated size whose estimated error meets `goal`.
// `scale` (>= 1) multiplies the per-vertex costs (ids, weights) when `fit` is of a sample.
// `basisBits` 8: the basis matrices' rounding (basis8Errors) counts in the error and their
// tables take a byte per entry plus a scale per shell; `entryWeight` is the fit's space.
// `maxVectors` (<= kMaxVectors) caps N'.
Choice chooseForFit(const MatrixFit& fit, std::size_t V, int channels, int order, MatrixPacking packing, int bits,
                    int basisBits, int maxVectors, std::span<const float> entryWeight, double goal, int* tried, double scale = 1.0) {
  const int levelsMax = quantLevels(bits), wb = bits / 8;
  const std::uint64_t E = matrixEntryCount(order, packing), C = static_cast<std::uint64_t>(channels);
  const std::uint64_t K = static_cast<std::uint64_t>(fit.clusters);
  std::vector<std::int32_t> ids(fit.clusterOf.begin(), fit.clusterOf.end());
  const double fixedBytes = static_cast<double>(kHeaderBytes + kPartEntryBytes * static_cast<std::uint64_t>(order + 2)) +
                            scale * estimateStreamGroupBytes(ids, 1, V, clusterIdBytes(fit.clusters)) + 4.0 * static_cast<double>(K);
  // Energy left after keeping N' vectors (per-cluster eigenvalues; clusters with fewer keep all).
  // With 8-bit basis entries, plus their rounding error (basis8Errors) for the kept ones.
  std::vector<double> resid(kMaxVectors + 1, 0.0);
  for (const ClusterFit& cf : fit.fits) {
    const std::vector<double> rounding = basisBits == 8 ? basis8Errors(cf, entryWeight, order, packing, channels) : std::vector<double>{};
    for (int n = 0; n <= kMaxVectors; ++n) {
      double r = cf.centredEnergy, added = 0.0;
      for (int j = 0; j < std::min(n, cf.vectors); ++j) {
        r -= cf.energy[static_cast<std::size_t>(j)];
        if (!rounding.empty()) added += cf.energy[static_cast<std::size_t>(j)] * rounding[static_cast<std::size_t>(j)];
      }
      resid[static_cast<std::size_t>(n)] += std::max(r, 0.0) + added;
    }
  }
  double maxWeight = 0.0;
  for (float w : fit.weights) maxWeight = std::max(maxWeight, std::fabs(static_cast<double>(w)));
  Choice best;
  for (int i = 0; i <= kDeltaSteps; ++i) {
    const double delta = i == kDeltaSteps ? 0.0 : maxWeight * std::ldexp(1.0, -(i + 1));
    const Quantised q = quantiseWeights(fit, V, delta, levelsMax);
    // Per vector j: quantisation error and estimated stream bytes; both add over j.
    double errSum = 0.0, streamSum = 0.0;
    for (int n = 0; n <= kMaxVectors; ++n) {
      ++*tried;
      const double tables = basisBits == 8 ? static_cast<double>(K * C * E) * (4.0 + n) + 4.0 * static_cast<double>(K) * n * order
                                           : static_cast<double>(K * C * E) * (4.0 + 2.0 * n);
      const double bytes = fixedBytes + streamSum + tables;
      if (resid[static_cast<std::size_t>(n)] + errSum <= goal && bytes < best.bytes) best = {bytes, n, delta};
      if (n == maxVectors || static_cast<std::uint64_t>(n) >= C * E) break;
      const std::size_t j = static_cast<std::size_t>(n);
      for (std::size_t v = 0; v < V; ++v) {
        const double e = static_cast<double>(fit.weights[v * kMaxVectors + j]) -
                         static_cast<double>(q.levels[j * V + v]) * static_cast<double>(q.steps[fit.clusterOf[v]]);
        errSum += e * e;
      }
      streamSum += scale * estimateStreamGroupBytes(std::span<const std::int32_t>(q.levels).subspan(j * V, V), 1, V, wb);
    }
  }
  return best;
}

// The weight of each packed entry (D = channels x entries, every channel alike) from the
// matrix rows' weights: w_i for a full-packed (i, j); a symmetric entry stands for both
// (i, j) and (j, i), whose squared errors weigh w_i^2 and w_j^2, so it takes
// sqrt((w_i^2 + w_j^2) / 2) (all ones stays all ones: the unweighted metric, each stored
// entry counted once). Empty rows: empty (unweighted).
std::vector<float> matrixEntryWeights(std::span<const double> rows, int order, MatrixPacking packing, int channels) {
  if (rows.empty()) return {};
  const std::size_t n2 = static_cast<std::size_t>(order) * static_cast<std::size_t>(order);
  const std::size_t E = matrixEntryCount(order, packing);
  std::vector<float> w(E * static_cast<std::size_t>(channels));
  for (std::size_t i = 0; i < n2; ++i) {
    for (std::size_t j = 0; j < n2; ++j) {
      if (packing == MatrixPacking::kSymmetric && j > i) continue;
      const double value = packing == MatrixPacking::kSymmetric && i != j
                               ? std::sqrt(0.5 * (rows[i] * rows[i] + rows[j] * rows[j]))
                               : rows[i];
      w[matrixEntryIndex(i, j, packing)] = static_cast<float>(value);
    }
  }
  for (std::size_t c = 1; c < static_cast<std::size_t>(channels); ++c) std::copy_n(w.data(), E, w.data() + c * E);
  return w;
}

std::vector<PartPayload> matrixCpcaParts(const MatrixFit& fit, std::size_t V, int order, MatrixPacking packing, int channels,
                                         int bits, int basisBits, int vectors, const Quantised& q) {
  const std::size_t E = matrixEntryCount(order, packing), C = static_cast<std::size_t>(channels), D = C * E;
  const std::size_t N = static_cast<std::size_t>(vectors);
  std::vector<PartPayload> parts;
  PartPayload ids;
  ids.type = TransferPartType::kClusters;
  std::vector<std::int32_t> idValues(fit.clusterOf.begin(), fit.clusterOf.end());
  putStreamGroup(idValues, 1, V, clusterIdBytes(static_cast<std::uint32_t>(fit.clusters)), ids.bytes);
  parts.push_back(std::move(ids));
  PartPayload w;
  w.type = TransferPartType::kWeights;
  for (float s : q.steps) putF32(w.bytes, s);
  putStreamGroup(std::span<const std::int32_t>(q.levels).first(N * V), N, V, bits / 8, w.bytes);
  parts.push_back(std::move(w));
  for (int b = 0; b < order; ++b) {
    PartPayload shell;
    shell.band = b;
    const std::size_t first = matrixEntryCount(b, packing), S = static_cast<std::size_t>(shellEntries(b, packing));
    for (const ClusterFit& cf : fit.fits)
      for (std::size_t c = 0; c < C; ++c)
        for (std::size_t e = 0; e < S; ++e) putF32(shell.bytes, cf.mean[c * E + first + e]);
    if (basisBits == 8) {
      // A scale per (cluster, basis matrix) of this shell, then the levels, same order. The
      // fit is back in the input's space here (weights divided out), so no entry weights.
      for (const ClusterFit& cf : fit.fits) {
        for (std::size_t j = 0; j < N; ++j) {
          const float scale = j < static_cast<std::size_t>(cf.vectors) ? basisScale(storedShell(cf, j, {}, order, b, packing, channels)) : 0.0f;
          putF32(shell.bytes, scale);
        }
      }
      for (const ClusterFit& cf : fit.fits)
        for (std::size_t j = 0; j < N; ++j) {
          const bool kept = j < static_cast<std::size_t>(cf.vectors);
          const std::vector<float> u = kept ? storedShell(cf, j, {}, order, b, packing, channels) : std::vector<float>(C * S, 0.0f);
          const float scale = basisScale(u);
          for (float x : u) putU8(shell.bytes, static_cast<std::uint8_t>(basisLevel(x, scale)));
        }
    } else {
      for (const ClusterFit& cf : fit.fits)
        for (std::size_t j = 0; j < N; ++j)
          for (std::size_t c = 0; c < C; ++c)
            for (std::size_t e = 0; e < S; ++e) {
              const float x = j < static_cast<std::size_t>(cf.vectors) ? cf.basis[j * D + c * E + first + e] : 0.0f;
              putU16(shell.bytes, floatToHalf(x));
            }
    }
    parts.push_back(std::move(shell));
  }
  return parts;
}

}  // namespace

Status encodeMatrixCpca(std::span<const float> packed, int order, MatrixPacking packing, int channels,
                        const TransferCodecSettings& settings, std::vector<std::uint8_t>* out, TransferEncodeReport* report) {
  const std::size_t E = matrixEntryCount(order, packing), C = static_cast<std::size_t>(channels), D = C * E;
  const std::size_t V = packed.size() / D;
  const int bits = settings.cpcaWeightBits, basisBits = settings.cpcaBasisBits;
  const int maxVectors = std::clamp(settings.cpcaMaxVectors, 0, kMaxVectors);
  const double target = settings.cpcaTargetError;
  const int maxClusters = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(settings.cpcaMaxClusters), V));
  // x: the matrices in the space the fit and the target live in, each entry times its rows'
  // weight (settings.cpcaMatrixRowWeights); without weights, the input itself.
  const std::vector<float> entryWeight = matrixEntryWeights(settings.cpcaMatrixRowWeights, order, packing, channels);
  std::vector<float> weighted;
  if (!entryWeight.empty()) {
    weighted.resize(packed.size());
    for (std::size_t v = 0; v < V; ++v)
      for (std::size_t d = 0; d < D; ++d) weighted[v * D + d] = packed[v * D + d] * entryWeight[d];
  }
  const std::span<const float> x = entryWeight.empty() ? packed : std::span<const float>(weighted);
  const std::string metric = entryWeight.empty() ? "" : "row-weighted ";
  double energy = 0.0;
  for (float e : x) energy += static_cast<double>(e) * e;

  // The search sample: every vertex, or an evenly strided subset (kSearchVertices).
  const bool sampled = V > kSearchVertices;
  const std::size_t S = sampled ? kSearchVertices : V;
  std::vector<float> sampleCopy;
  std::span<const float> sample = x;
  if (sampled) {
    sampleCopy.resize(S * D);
    for (std::size_t i = 0; i < S; ++i) {
      const std::size_t v = i * V / S;
      std::copy_n(x.data() + v * D, D, sampleCopy.data() + i * D);
    }
    sample = sampleCopy;
  }
  double sampleEnergy = 0.0;
  for (float e : sample) sampleEnergy += static_cast<double>(e) * e;

  // k-means points: the data itself when it is small, else its coordinates in the global
  // sketch (a subspace fitted on the sample, every vertex projected once).
  std::vector<float> projected, sampleProjected;
  std::span<const float> points = x, samplePoints = sample;
  int pointDims = static_cast<int>(D);
  if (D > static_cast<std::size_t>(kSketch)) {
    std::vector<double> mean(D, 0.0);
    for (std::size_t v = 0; v < S; ++v)
      for (std::size_t d = 0; d < D; ++d) mean[d] += sample[v * D + d];
    std::vector<float> meanF(D);
    for (std::size_t d = 0; d < D; ++d) meanF[d] = static_cast<float>(mean[d] / static_cast<double>(S));
    std::vector<std::uint32_t> all(S);
    for (std::size_t v = 0; v < S; ++v) all[v] = static_cast<std::uint32_t>(v);
    Subspace sub = sketch(sample, D, all, meanF.data(), kSketch, settings.seed ^ 0x5eedu);
    if (sub.dims > 0) {
      pointDims = sub.dims;
      const std::size_t L = static_cast<std::size_t>(sub.dims);
      if (sampled) {
        projected.resize(V * L);
        std::vector<float> row(D);
        for (std::size_t v = 0; v < V; ++v) {
          for (std::size_t d = 0; d < D; ++d) row[d] = x[v * D + d] - meanF[d];
          rowTimes(row.data(), sub.q.data(), D, L, &projected[v * L]);
        }
        sampleProjected = std::move(sub.coords);
      } else {
        projected = std::move(sub.coords);
      }
      points = projected;
      samplePoints = sampled ? std::span<const float>(sampleProjected) : std::span<const float>(projected);
    }
  }

  int tried = 0;
  // Cluster count: 1, 2, 4, ... on the sample, while it keeps improving the estimate.
  const int sampleMaxClusters = sampled ? std::min<int>(maxClusters, static_cast<int>(S / kMinSampleMembers)) : maxClusters;
  const double sampleGoal = kEstimateMargin * kEstimateMargin * target * target * sampleEnergy;
  const double scale = static_cast<double>(V) / static_cast<double>(S);
  MatrixFit best;
  Choice bestChoice;
  int bestK = 0, worseInARow = 0, previousClusters = 0;
  for (int k = 1; k <= sampleMaxClusters;
       k = k >= sampleMaxClusters ? sampleMaxClusters + 1 : std::min(2 * k, sampleMaxClusters)) {
    // The means alone of k clusters outweigh the best so far: larger k cannot win.
    if (static_cast<double>(k) * static_cast<double>(D) * 4.0 > bestChoice.bytes) break;
    MatrixFit fit = fitMatrixCpca(sample, S, D, k, settings.seed, samplePoints, pointDims, sampleEnergy);
    if (fit.clusters == previousClusters) break;  // no more distinct points to split
    previousClusters = fit.clusters;
    const Choice c = chooseForFit(fit, S, channels, order, packing, bits, basisBits, maxVectors, entryWeight, sampleGoal, &tried, scale);
    const bool improved = c.bytes < bestChoice.bytes;
    if (improved) {
      bestChoice = c;
      bestK = k;
      if (!sampled) best = std::move(fit);
    }
    worseInARow = improved ? 0 : worseInARow + 1;
    if (bestChoice.bytes < INFINITY && worseInARow >= 2) break;
  }
  const double goal = kEstimateMargin * kEstimateMargin * target * target * energy;
  if (sampled) {
    // The winner on every vertex; where the sample misled (the full fit misses the goal),
    // twice the clusters, up to the limit. When no sampled count reached the goal, the
    // search goes on from the sample's largest count.
    for (int k = bestK > 0 ? bestK : std::max(sampleMaxClusters, 1);; k = std::min(2 * k, maxClusters)) {
      best = fitMatrixCpca(x, V, D, k, settings.seed, points, pointDims, energy);
      bestChoice = chooseForFit(best, V, channels, order, packing, bits, basisBits, maxVectors, entryWeight, goal, &tried);
      if (bestChoice.bytes < INFINITY || k >= maxClusters || best.clusters < k) break;
    }
  }
  if (!(bestChoice.bytes < INFINITY)) {
    return Status::error(StatusCode::kInvalidArgument,
                         "matrix CPCA cannot reach the target " + metric + "relative error " + std::to_string(target) + " with " +
                             std::to_string(bits) + "-bit weights" + (basisBits == 8 ? ", 8-bit basis entries" : "") +
                             " and at most " + std::to_string(maxVectors) + " basis matrices per cluster; use " +
                             (maxVectors < kMaxVectors ? "a larger basis limit, " : "") +
                             (bits < 16 ? "16-bit weights, " : "") + (basisBits == 8 ? "binary16 basis entries, " : "") +
                             "more clusters (the limit was " + std::to_string(maxClusters) + ") or a larger target");
  }

  BlobHeader header;
  header.encoding = TransferEncoding::kCpca;
  header.matrix = true;
  header.packing = packing;
  header.weightBits = bits;
  header.order = order;
  header.channels = channels;
  header.vertexCount = static_cast<std::uint32_t>(V);
  header.clusterCount = static_cast<std::uint32_t>(best.clusters);
  header.vectors = bestChoice.vectors;
  header.basisBits = basisBits;
  // Back from the weighted space: the stored means and basis matrices are of the input's
  // matrices, so decoders and renderers never see the weights.
  if (!entryWeight.empty()) {
    for (ClusterFit& cf : best.fits) {
      for (std::size_t d = 0; d < D; ++d) cf.mean[d] /= entryWeight[d];
      for (std::size_t j = 0; j < static_cast<std::size_t>(cf.vectors); ++j)
        for (std::size_t d = 0; d < D; ++d) cf.basis[j * D + d] /= entryWeight[d];
    }
  }
  std::vector<float> decoded(x.size());
  double delta = bestChoice.delta;
  for (int attempt = 0; attempt <= kVerifyRetries; ++attempt) {
    const Quantised q = quantiseWeights(best, V, delta, quantLevels(bits));
    std::vector<std::uint8_t> blob;
    assembleBlob(header, matrixCpcaParts(best, V, order, packing, channels, bits, basisBits, bestChoice.vectors, q), &blob);
    if (Status s = decodeTransferMatrix(blob, order, decoded); !s.isOk()) {
      return Status::error(StatusCode::kInvalidArgument,
                           "the matrix transfer cannot be stored as CPCA within the transfer range: " + s.message());
    }
    double maxAbs = 0.0;  // of the input's entries, unweighted
    double rel = matrixRelativeError(packed, decoded, energy, &maxAbs);
    if (!entryWeight.empty()) {
      for (std::size_t v = 0; v < V; ++v)
        for (std::size_t d = 0; d < D; ++d) decoded[v * D + d] *= entryWeight[d];
      double weightedMaxAbs = 0.0;
      rel = matrixRelativeError(x, decoded, energy, &weightedMaxAbs);
    }
    if (rel <= target) {
      if (report) {
        *report = TransferEncodeReport{};
        report->bytes = blob.size();
        report->clusters = best.clusters;
        report->vectorsPerBand = {bestChoice.vectors};
        report->relativeError = rel;
        report->maxAbsError = maxAbs;
        report->candidatesTried = tried;
      }
      *out = std::move(blob);
      return Status::ok();
    }
    // The estimate missed (basis rounding, float sums): a finer step, then the tightest.
    delta = attempt + 1 == kVerifyRetries ? 0.0 : delta * 0.7;
  }
  return Status::error(StatusCode::kInvalidArgument,
                       "matrix CPCA could not verify the target " + metric + "relative error " + std::to_string(target) + " with " +
                           std::to_string(bits) + "-bit weights" + (basisBits == 8 ? " and 8-bit basis entries" : "") +
                           "; use 16-bit weights" + (basisBits == 8 ? ", binary16 basis entries" : "") + " or a larger target");
}

}  // namespace prt::transfer_codec
