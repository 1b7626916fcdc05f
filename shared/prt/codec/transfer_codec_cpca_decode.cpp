// decodeCpcaTransfer and cpcaReconstruct (prt/transfer_codec.h): the CPCA parts as the
// renderer uses them, and their expansion to plain transfer.
#include <algorithm>
#include <cmath>
#include <string>

#include "prt/transfer_codec.h"
#include "transfer_codec_container.h"
#include "transfer_codec_decode_util.h"
#include "prt/half_float.h"
#include "transfer_codec_streams.h"

namespace prt {
namespace {

using namespace transfer_codec;  // NOLINT: the codec's own internals

Status corrupt(std::string message) { return Status::error(StatusCode::kCorrupt, std::move(message)); }

Status decodeClusters(std::span<const std::uint8_t> bytes, const TransferBlobInfo& info, CpcaTransfer* out) {
  const TransferPartInfo& part = info.parts[0];
  if (Status s = checkPartCrc(bytes, 0, part); !s.isOk()) return s;
  const int width = clusterIdBytes(info.clusterCount);
  std::vector<std::int32_t> ids(info.vertexCount);
  if (!getStream(bytes.data() + part.offset, 1, info.vertexCount, width, 0, ids)) {
    return corrupt(partName(0, part) + ": unknown filter " + std::to_string(bytes[static_cast<std::size_t>(part.offset)]));
  }
  const std::uint32_t mask = width == 1 ? 0xffu : 0xffffu;
  out->clusterOf.resize(info.vertexCount);
  for (std::size_t v = 0; v < ids.size(); ++v) {
    const std::uint32_t id = static_cast<std::uint32_t>(ids[v]) & mask;
    if (id >= info.clusterCount) {
      return corrupt(partName(0, part) + ": vertex " + std::to_string(v) + " is in cluster " + std::to_string(id) +
                     ", not below the cluster count " + std::to_string(info.clusterCount));
    }
    out->clusterOf[v] = id;
  }
  return Status::ok();
}

Status decodeCpcaBand(std::span<const std::uint8_t> bytes, const TransferBlobInfo& info, std::size_t index,
                      const std::vector<std::uint32_t>& clusterOf, CpcaBand* out) {
  const TransferPartInfo& part = info.parts[index];
  const std::string name = partName(index, part);
  if (Status s = checkPartCrc(bytes, index, part); !s.isOk()) return s;
  const std::size_t K = info.clusterCount, V = info.vertexCount;
  const int dims = info.channels * (2 * part.band + 1), weightBytes = info.weightBits / 8;
  const int levels = quantLevels(info.weightBits);
  if (part.size < 4) return corrupt(name + " is " + std::to_string(part.size) + " bytes, too short for its vector count");
  const std::uint8_t* p = bytes.data() + part.offset;
  const std::uint32_t vectors = readLe32(p);
  if (vectors > static_cast<std::uint32_t>(dims)) {
    return corrupt(name + ": " + std::to_string(vectors) + " principal vectors, more than the band's " + std::to_string(dims) +
                   " dimensions");
  }
  const int n = static_cast<int>(vectors);
  const std::uint64_t want = cpcaBandPartBytes(info.clusterCount, dims, n, V, weightBytes);
  if (part.size != want) {
    return corrupt(name + " is " + std::to_string(part.size) + " bytes, expected " + std::to_string(want) + " for " +
                   std::to_string(n) + " vectors");
  }
  const std::size_t D = static_cast<std::size_t>(dims), N = static_cast<std::size_t>(n);
  out->band = part.band;
  out->dims = dims;
  out->vectors = n;
  p += 4;
  std::vector<float> steps(K);
  for (std::size_t k = 0; k < K; ++k, p += 4) {
    steps[k] = readLeF32(p);
    if (Status s = checkStep(steps[k], levels, name + ": weight step of cluster " + std::to_string(k)); !s.isOk()) return s;
  }
  out->means.resize(K * D);
  for (std::size_t i = 0; i < K * D; ++i, p += 4) {
    out->means[i] = readLeF32(p);
    if (!(std::fabs(out->means[i]) <= kMaxTransferMagnitude)) {  // NaN fails too
      return corrupt(name + ": mean of cluster " + std::to_string(i / D) + ", dimension " + std::to_string(i % D) +
                     " is not finite or beyond the transfer range (65504)");
    }
  }
  out->basis.resize(K * N * D);
  for (std::size_t i = 0; i < K * N * D; ++i, p += 2) {
    const std::uint16_t h = readLe16(p);
    if (!isFiniteHalf(h)) {
      return corrupt(name + ": principal vector " + std::to_string((i / D) % N) + " of cluster " + std::to_string(i / (D * N)) +
                     " is not finite");
    }
    out->basis[i] = halfToFloat(h);
  }
  out->weights.resize(V * N);
  out->levels.resize(V * N);
  std::vector<std::int32_t> levelsOf(V);
  std::vector<std::int32_t> largestLevel(K * N, 0);  // per cluster and vector: max |level| used
  for (std::size_t j = 0; j < N; ++j) {
    if (!getStream(p, N, V, weightBytes, j, levelsOf)) {
      return corrupt(name + ": weight " + std::to_string(j) + " has an unknown filter " + std::to_string(p[j]));
    }
    for (std::size_t v = 0; v < V; ++v) {
      const std::int32_t q = levelsOf[v];
      if (q < -levels || q > levels) {
        return corrupt(name + ": weight " + std::to_string(j) + " of vertex " + std::to_string(v) + " is level " +
                       std::to_string(q) + ", outside +-" + std::to_string(levels));
      }
      out->weights[v * N + j] = static_cast<float>(q) * steps[clusterOf[v]];
      out->levels[v * N + j] = static_cast<std::int16_t>(q);  // |q| <= 32767: checked above
      std::int32_t& largest = largestLevel[clusterOf[v] * N + j];
      largest = std::max(largest, q < 0 ? -q : q);
    }
  }
  // Every value a vertex of cluster k reconstructs, in any renderer's order of summation, is
  // within |mean| + sum_j step |level_j| max|basis_j|: bounding that per cluster keeps the
  // decoded transfer inside kMaxTransferMagnitude without reconstructing it.
  for (std::size_t k = 0; k < K; ++k) {
    double bound = 0.0;
    for (std::size_t d = 0; d < D; ++d) bound = std::max(bound, std::fabs(static_cast<double>(out->means[k * D + d])));
    for (std::size_t j = 0; j < N; ++j) {
      double basisMax = 0.0;
      for (std::size_t d = 0; d < D; ++d) basisMax = std::max(basisMax, std::fabs(static_cast<double>(out->basis[(k * N + j) * D + d])));
      bound += static_cast<double>(steps[k]) * largestLevel[k * N + j] * basisMax;
    }
    if (bound > kMaxTransferMagnitudeRounded) {
      return corrupt(name + ": cluster " + std::to_string(k) + " can reconstruct values up to " + std::to_string(bound) +
                     ", beyond the transfer range (65504)");
    }
  }
  out->steps = std::move(steps);
  return Status::ok();
}

}  // namespace

Status decodeCpcaTransfer(std::span<const std::uint8_t> bytes, int bands, CpcaTransfer* out) {
  TransferBlobInfo info;
  if (Status s = readTransferBlobInfo(bytes, &info); !s.isOk()) return s;
  if (info.encoding != TransferEncoding::kCpca) {
    return Status::error(StatusCode::kInvalidArgument,
                         std::string("the transfer blob is ") + transferEncodingName(info.encoding) + ", not CPCA");
  }
  if (info.matrix) {
    return Status::error(StatusCode::kInvalidArgument, "the transfer blob holds matrices: decode it with decodeCpcaMatrixTransfer");
  }
  if (Status s = checkBandRequest(info, bands); !s.isOk()) return s;
  CpcaTransfer cpca;
  cpca.order = info.order;
  cpca.channels = info.channels;
  cpca.vertexCount = info.vertexCount;
  cpca.clusterCount = info.clusterCount;
  cpca.weightBits = info.weightBits;
  if (Status s = decodeClusters(bytes, info, &cpca); !s.isOk()) return s;
  cpca.bands.resize(static_cast<std::size_t>(bands));
  for (int l = 0; l < bands; ++l) {
    const std::size_t index = static_cast<std::size_t>(l) + 1;
    if (Status s = decodeCpcaBand(bytes, info, index, cpca.clusterOf, &cpca.bands[static_cast<std::size_t>(l)]); !s.isOk()) return s;
  }
  *out = std::move(cpca);
  return Status::ok();
}

Status cpcaReconstruct(const CpcaTransfer& cpca, std::span<float> out) {
  const std::size_t V = cpca.vertexCount, K = cpca.clusterCount, C = static_cast<std::size_t>(cpca.channels);
  const std::size_t bands = cpca.bands.size(), b2 = bands * bands;
  if (out.size() != V * C * b2) {
    return Status::error(StatusCode::kSizeMismatch, "output holds " + std::to_string(out.size()) + " floats, the " +
                                                        std::to_string(bands) + "-band transfer needs " + std::to_string(V * C * b2));
  }
  bool consistent = cpca.clusterOf.size() == V && (C == 1 || C == 3);
  for (std::size_t l = 0; l < bands && consistent; ++l) {
    const CpcaBand& b = cpca.bands[l];
    const std::size_t D = static_cast<std::size_t>(b.dims), N = static_cast<std::size_t>(b.vectors);
    consistent = b.band == static_cast<int>(l) && D == C * (2 * l + 1) && b.vectors >= 0 && N <= D && b.means.size() == K * D &&
                 b.basis.size() == K * N * D && b.weights.size() == V * N;
  }
  for (std::size_t v = 0; v < V && consistent; ++v) consistent = cpca.clusterOf[v] < K;
  if (!consistent) return Status::error(StatusCode::kSizeMismatch, "CPCA transfer arrays disagree with its counts");

  for (std::size_t v = 0; v < V; ++v) {
    const std::size_t k = cpca.clusterOf[v];
    for (std::size_t l = 0; l < bands; ++l) {
      const CpcaBand& b = cpca.bands[l];
      const std::size_t D = static_cast<std::size_t>(b.dims), N = static_cast<std::size_t>(b.vectors), width = 2 * l + 1;
      const float* mean = &b.means[k * D];
      const float* basis = b.basis.data() + k * N * D;
      const float* w = b.weights.data() + v * N;
      for (std::size_t d = 0; d < D; ++d) {
        float x = mean[d];
        for (std::size_t j = 0; j < N; ++j) x += w[j] * basis[j * D + d];
        if (!std::isfinite(x)) {
          return Status::error(StatusCode::kCorrupt, "CPCA transfer of vertex " + std::to_string(v) + ", band " + std::to_string(l) +
                                                         " reconstructs to a non-finite value");
        }
        out[(v * C + d / width) * b2 + l * l + d % width] = x;
      }
    }
  }
  return Status::ok();
}

}  // namespace prt
