// CPCA model fitting, quantisation and size/error estimates (prt/transfer_codec_cpca.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "transfer_codec_cpca.h"
#include "transfer_codec_eigen.h"
#include "prt/half_float.h"
#include "transfer_codec_kmeans.h"
#include "transfer_codec_streams.h"

namespace prt::transfer_codec {
namespace {

// Band l's vector of vertex v: d = c*(2l+1) + (m+l) <- transfer[(v*C + c)*n^2 + l^2 + m+l].
void bandVector(std::span<const float> transfer, std::size_t v, int order, int channels, int band, double* out) {
  const std::size_t n2 = static_cast<std::size_t>(order * order), width = static_cast<std::size_t>(2 * band + 1);
  const std::size_t first = static_cast<std::size_t>(band * band);
  for (std::size_t c = 0; c < static_cast<std::size_t>(channels); ++c) {
    const float* row = transfer.data() + (v * static_cast<std::size_t>(channels) + c) * n2 + first;
    for (std::size_t m = 0; m < width; ++m) out[c * width + m] = row[m];
  }
}

// Step of a cluster and band: delta, or more where the weights' range needs it to fit Q
// levels; a float, rounded up so that range / step <= Q holds exactly.
float clusterStep(double delta, double range, int levels) {
  const double wanted = std::max(delta, range / levels);
  // Normal floats only: from a normal start the loop below runs at most twice.
  float step = std::max(static_cast<float>(wanted), std::numeric_limits<float>::min());
  while (static_cast<double>(step) * levels < range) step = std::nextafter(step, 2.0f * step + 1.0f);
  return step;
}

std::int32_t quantiseWeight(double w, float step, int levels) {
  if (step <= 0.0f) return 0;
  const double q = std::nearbyint(w / static_cast<double>(step));
  return static_cast<std::int32_t>(std::clamp(q, -static_cast<double>(levels), static_cast<double>(levels)));
}

}  // namespace

CpcaFit fitCpca(std::span<const float> transfer, int order, int channels, int clusters, std::uint64_t seed) {
  CpcaFit fit;
  fit.order = order;
  fit.channels = channels;
  const std::size_t stride = static_cast<std::size_t>(channels * order * order);
  fit.vertices = transfer.size() / stride;
  for (float x : transfer) fit.energy += static_cast<double>(x) * x;

  KMeansOptions km;
  km.clusters = clusters;
  km.seed = seed;
  KMeansResult r = kMeans(transfer, fit.vertices, static_cast<int>(stride), km);
  fit.clusters = r.clusters;
  fit.clusterOf = std::move(r.assignment);

  // Vertices grouped by cluster (counting sort), so each cluster's PCA needs one scratch matrix.
  const std::size_t K = static_cast<std::size_t>(fit.clusters);
  std::vector<std::size_t> start(K + 1, 0), members(fit.vertices);
  for (std::uint32_t k : fit.clusterOf) ++start[k + 1];
  for (std::size_t k = 0; k < K; ++k) start[k + 1] += start[k];
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t v = 0; v < fit.vertices; ++v) members[fill[fit.clusterOf[v]]++] = v;
  }

  fit.bands.resize(static_cast<std::size_t>(order));
  for (int l = 0; l < order; ++l) {
    CpcaBandFit& b = fit.bands[static_cast<std::size_t>(l)];
    b.dims = channels * (2 * l + 1);
    const std::size_t D = static_cast<std::size_t>(b.dims);
    b.means.assign(K * D, 0.0f);
    b.basis.assign(K * D * D, 0);
    b.componentEnergy.assign(D, 0.0);
    b.weights.assign(fit.vertices * D, 0.0f);
    b.maxAbsWeight.assign(K * D, 0.0f);
    std::vector<double> x(D), mean(D), scatter(D * D), axes(D * D);
    for (std::size_t k = 0; k < K; ++k) {
      const std::size_t first = start[k], last = start[k + 1];
      std::fill(mean.begin(), mean.end(), 0.0);
      for (std::size_t i = first; i < last; ++i) {
        bandVector(transfer, members[i], order, channels, l, x.data());
        for (std::size_t d = 0; d < D; ++d) mean[d] += x[d];
      }
      float* storedMean = &b.means[k * D];
      for (std::size_t d = 0; d < D; ++d) storedMean[d] = static_cast<float>(mean[d] / static_cast<double>(last - first));
      // Scatter about the stored (float) mean: the decoder adds that mean back.
      std::fill(scatter.begin(), scatter.end(), 0.0);
      for (std::size_t i = first; i < last; ++i) {
        bandVector(transfer, members[i], order, channels, l, x.data());
        for (std::size_t d = 0; d < D; ++d) x[d] -= storedMean[d];
        for (std::size_t p = 0; p < D; ++p) {
          for (std::size_t q = 0; q <= p; ++q) scatter[p * D + q] += x[p] * x[q];
        }
      }
      for (std::size_t p = 0; p < D; ++p) {
        for (std::size_t q = 0; q < p; ++q) scatter[q * D + p] = scatter[p * D + q];
      }
      const SymmetricEigen eig = symmetricEigen(b.dims, scatter);
      for (std::size_t j = 0; j < D; ++j) {
        b.componentEnergy[j] += std::max(0.0, eig.values[j]);
        for (std::size_t d = 0; d < D; ++d) {
          const std::uint16_t h = floatToHalf(static_cast<float>(eig.vectors[j * D + d]));
          b.basis[(k * D + j) * D + d] = h;
          axes[j * D + d] = halfToFloat(h);
        }
      }
      for (std::size_t i = first; i < last; ++i) {
        const std::size_t v = members[i];
        bandVector(transfer, v, order, channels, l, x.data());
        for (std::size_t d = 0; d < D; ++d) x[d] -= storedMean[d];
        for (std::size_t j = 0; j < D; ++j) {
          double w = 0.0;
          for (std::size_t d = 0; d < D; ++d) w += x[d] * axes[j * D + d];
          b.weights[v * D + j] = static_cast<float>(w);
          float& m = b.maxAbsWeight[k * D + j];
          m = std::max(m, static_cast<float>(std::fabs(w)));
        }
      }
    }
  }
  return fit;
}

CpcaQuantisation chooseQuantisation(const CpcaFit& fit, double delta, double kappa, int weightBits) {
  CpcaQuantisation q;
  q.delta = delta;
  const int levels = quantLevels(weightBits);
  const std::size_t K = static_cast<std::size_t>(fit.clusters);
  const double threshold = kappa * static_cast<double>(fit.vertices) * delta * delta;
  q.vectors.resize(fit.bands.size());
  q.steps.assign(fit.bands.size() * K, 0.0f);
  for (std::size_t l = 0; l < fit.bands.size(); ++l) {
    const CpcaBandFit& b = fit.bands[l];
    const std::size_t D = static_cast<std::size_t>(b.dims);
    int n = 0;
    while (n < b.dims && b.componentEnergy[static_cast<std::size_t>(n)] > 0.0 &&
           b.componentEnergy[static_cast<std::size_t>(n)] >= threshold) {
      ++n;
    }
    q.vectors[l] = n;
    if (n == 0) continue;
    for (std::size_t k = 0; k < K; ++k) {
      double range = 0.0;
      for (std::size_t j = 0; j < static_cast<std::size_t>(n); ++j) range = std::max(range, static_cast<double>(b.maxAbsWeight[k * D + j]));
      q.steps[l * K + k] = range > 0.0 ? clusterStep(delta, range, levels) : 0.0f;
    }
  }
  return q;
}

double estimateSquaredError(const CpcaFit& fit, const CpcaQuantisation& q, int weightBits) {
  const int levels = quantLevels(weightBits);
  const std::size_t K = static_cast<std::size_t>(fit.clusters);
  double total = 0.0;
  for (std::size_t l = 0; l < fit.bands.size(); ++l) {
    const CpcaBandFit& b = fit.bands[l];
    const std::size_t D = static_cast<std::size_t>(b.dims), n = static_cast<std::size_t>(q.vectors[l]);
    for (std::size_t v = 0; v < fit.vertices; ++v) {
      const float step = q.steps[l * K + fit.clusterOf[v]];
      const float* w = &b.weights[v * D];
      for (std::size_t j = 0; j < n; ++j) {
        const double e = static_cast<double>(w[j]) - static_cast<double>(quantiseWeight(w[j], step, levels)) * step;
        total += e * e;
      }
      for (std::size_t j = n; j < D; ++j) total += static_cast<double>(w[j]) * w[j];
    }
  }
  return total;
}

namespace {

std::vector<std::int32_t> clusterIdValues(const CpcaFit& fit) {
  const int width = clusterIdBytes(static_cast<std::uint32_t>(fit.clusters));
  std::vector<std::int32_t> ids(fit.vertices);
  for (std::size_t v = 0; v < fit.vertices; ++v) ids[v] = wrapToWidth(fit.clusterOf[v], width);
  return ids;
}

// Band l's quantised weights, [vector][vertex].
std::vector<std::int32_t> bandWeightValues(const CpcaFit& fit, const CpcaQuantisation& q, std::size_t l, int weightBits) {
  const CpcaBandFit& b = fit.bands[l];
  const std::size_t D = static_cast<std::size_t>(b.dims), n = static_cast<std::size_t>(q.vectors[l]);
  const std::size_t K = static_cast<std::size_t>(fit.clusters);
  const int levels = quantLevels(weightBits);
  std::vector<std::int32_t> values(n * fit.vertices);
  for (std::size_t v = 0; v < fit.vertices; ++v) {
    const float step = q.steps[l * K + fit.clusterOf[v]];
    for (std::size_t j = 0; j < n; ++j) values[j * fit.vertices + v] = quantiseWeight(b.weights[v * D + j], step, levels);
  }
  return values;
}

}  // namespace

double estimateCpcaBytes(const CpcaFit& fit, const CpcaQuantisation& q, int weightBits) {
  const int idWidth = clusterIdBytes(static_cast<std::uint32_t>(fit.clusters));
  double total = static_cast<double>(kHeaderBytes + kPartEntryBytes * (fit.bands.size() + 1));
  total += estimateStreamGroupBytes(clusterIdValues(fit), 1, fit.vertices, idWidth);
  const double K = fit.clusters;
  for (std::size_t l = 0; l < fit.bands.size(); ++l) {
    const double D = fit.bands[l].dims, n = q.vectors[l];
    total += 4.0 + 4.0 * K + 4.0 * K * D + 2.0 * K * n * D;
    total += estimateStreamGroupBytes(bandWeightValues(fit, q, l, weightBits), static_cast<std::size_t>(q.vectors[l]),
                                      fit.vertices, weightBits / 8);
  }
  return total;
}

std::vector<PartPayload> cpcaParts(const CpcaFit& fit, const CpcaQuantisation& q, int weightBits) {
  std::vector<PartPayload> parts;
  PartPayload ids;
  ids.type = TransferPartType::kClusters;
  putStreamGroup(clusterIdValues(fit), 1, fit.vertices, clusterIdBytes(static_cast<std::uint32_t>(fit.clusters)), ids.bytes);
  parts.push_back(std::move(ids));
  const std::size_t K = static_cast<std::size_t>(fit.clusters);
  for (std::size_t l = 0; l < fit.bands.size(); ++l) {
    const CpcaBandFit& b = fit.bands[l];
    const std::size_t D = static_cast<std::size_t>(b.dims), n = static_cast<std::size_t>(q.vectors[l]);
    PartPayload p;
    p.band = static_cast<int>(l);
    putU32(p.bytes, static_cast<std::uint32_t>(n));
    for (std::size_t k = 0; k < K; ++k) putF32(p.bytes, q.steps[l * K + k]);
    for (float m : b.means) putF32(p.bytes, m);
    for (std::size_t k = 0; k < K; ++k) {
      for (std::size_t j = 0; j < n; ++j) {
        for (std::size_t d = 0; d < D; ++d) putU16(p.bytes, b.basis[(k * D + j) * D + d]);
      }
    }
    putStreamGroup(bandWeightValues(fit, q, l, weightBits), n, fit.vertices, weightBits / 8, p.bytes);
    parts.push_back(std::move(p));
  }
  return parts;
}

}  // namespace prt::transfer_codec
