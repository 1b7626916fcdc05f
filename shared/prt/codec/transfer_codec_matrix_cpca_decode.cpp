// decodeCpcaMatrixTransfer and cpcaMatrixReconstruct (prt/transfer_codec.h,
// docs/transfer-codec.md "Matrices"): the matrix CPCA parts as a renderer uses them, and
// their expansion. Every part's checksum is checked before its bytes are read, every value
// is range-checked, and what a cluster can reconstruct is bounded before anything is expanded.
#include <algorithm>
#include <cmath>
#include <string>

#include "prt/transfer_codec.h"
#include "transfer_codec_basis8.h"
#include "transfer_codec_container.h"
#include "transfer_codec_decode_util.h"
#include "prt/half_float.h"
#include "transfer_codec_streams.h"

namespace prt {
namespace {

using namespace transfer_codec;  // NOLINT: the codec's own internals

Status corrupt(std::string message) { return Status::error(StatusCode::kCorrupt, std::move(message)); }

Status decodeIds(std::span<const std::uint8_t> bytes, const TransferBlobInfo& info, CpcaMatrixTransfer* out) {
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

// Weights part: a step per cluster, then `vectors` streams of levels. `largest` receives,
// per cluster and vector, the largest |level| used (for the range bound).
Status decodeWeights(std::span<const std::uint8_t> bytes, const TransferBlobInfo& info, CpcaMatrixTransfer* out,
                     std::vector<std::int32_t>* largest) {
  const TransferPartInfo& part = info.parts[1];
  const std::string name = partName(1, part);
  if (Status s = checkPartCrc(bytes, 1, part); !s.isOk()) return s;
  const std::size_t K = info.clusterCount, V = info.vertexCount, N = static_cast<std::size_t>(info.vectors);
  const int levels = quantLevels(info.weightBits), weightBytes = info.weightBits / 8;
  const std::uint8_t* p = bytes.data() + part.offset;
  out->steps.resize(K);
  for (std::size_t k = 0; k < K; ++k, p += 4) {
    out->steps[k] = readLeF32(p);
    if (Status s = checkStep(out->steps[k], levels, name + ": weight step of cluster " + std::to_string(k)); !s.isOk()) return s;
  }
  out->weights.resize(V * N);
  out->levels.resize(V * N);
  largest->assign(K * N, 0);
  std::vector<std::int32_t> levelsOf(V);
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
      const std::size_t k = out->clusterOf[v];
      out->weights[v * N + j] = static_cast<float>(q) * out->steps[k];
      out->levels[v * N + j] = static_cast<std::int16_t>(q);  // |q| <= 32767: checked above
      std::int32_t& l = (*largest)[k * N + j];
      l = std::max(l, q < 0 ? -q : q);
    }
  }
  return Status::ok();
}

// 8-bit basis entries of one shell (version 1.2): K * N float32 scales [cluster][basis],
// then K * N * C * S int8 levels [cluster][basis][channel][shell entry]; `p` points at the
// scales. A scale must be finite, >= 0 and keep its 127 levels within the transfer range,
// a level within +-127 (-128 is never written).
template <typename At>
Status decodeBasis8(const std::uint8_t* p, const std::string& name, std::size_t K, std::size_t N, std::size_t C, std::size_t S,
                    At&& at) {
  const std::uint8_t* levels = p + 4 * K * N;
  for (std::size_t k = 0; k < K; ++k)
    for (std::size_t j = 0; j < N; ++j) {
      const float scale = readLeF32(p + 4 * (k * N + j));
      const std::string what = name + ": basis scale of cluster " + std::to_string(k) + ", basis matrix " + std::to_string(j);
      if (Status s = checkStep(scale, kBasisLevels, what); !s.isOk()) return s;
      for (std::size_t c = 0; c < C; ++c)
        for (std::size_t e = 0; e < S; ++e, ++levels) {
          const int q = static_cast<std::int8_t>(*levels);
          if (q < -kBasisLevels) {
            return corrupt(name + ": basis matrix " + std::to_string(j) + " of cluster " + std::to_string(k) + " has level " +
                           std::to_string(q) + ", outside +-" + std::to_string(kBasisLevels));
          }
          at(k, j + 1, c, e) = basisValue(q, scale);
        }
    }
  return Status::ok();
}

// Shell part `band` into out->matrices ([cluster][matrix][channel][entry < Eb]).
Status decodeShellPart(std::span<const std::uint8_t> bytes, const TransferBlobInfo& info, int band, std::size_t Eb,
                       CpcaMatrixTransfer* out) {
  const std::size_t index = static_cast<std::size_t>(band) + 2;
  const TransferPartInfo& part = info.parts[index];
  const std::string name = partName(index, part);
  if (Status s = checkPartCrc(bytes, index, part); !s.isOk()) return s;
  const std::size_t K = info.clusterCount, N = static_cast<std::size_t>(info.vectors), C = static_cast<std::size_t>(info.channels);
  const std::size_t first = matrixEntryCount(band, info.packing), S = static_cast<std::size_t>(shellEntries(band, info.packing));
  const std::uint8_t* p = bytes.data() + part.offset;
  auto at = [&](std::size_t k, std::size_t m, std::size_t c, std::size_t e) -> float& {
    return out->matrices[((k * (N + 1) + m) * C + c) * Eb + first + e];
  };
  for (std::size_t k = 0; k < K; ++k)
    for (std::size_t c = 0; c < C; ++c)
      for (std::size_t e = 0; e < S; ++e, p += 4) {
        const float x = readLeF32(p);
        if (!(std::fabs(x) <= kMaxTransferMagnitude)) {  // NaN fails too
          return corrupt(name + ": mean of cluster " + std::to_string(k) + ", channel " + std::to_string(c) + ", entry " +
                         std::to_string(first + e) + " is not finite or beyond the transfer range (65504)");
        }
        at(k, 0, c, e) = x;
      }
  if (info.basisBits == 8) return decodeBasis8(p, name, K, N, C, S, at);
  for (std::size_t k = 0; k < K; ++k)
    for (std::size_t j = 0; j < N; ++j)
      for (std::size_t c = 0; c < C; ++c)
        for (std::size_t e = 0; e < S; ++e, p += 2) {
          const std::uint16_t h = readLe16(p);
          if (!isFiniteHalf(h)) {
            return corrupt(name + ": basis matrix " + std::to_string(j) + " of cluster " + std::to_string(k) + " is not finite");
          }
          at(k, j + 1, c, e) = halfToFloat(h);
        }
  return Status::ok();
}

}  // namespace

Status decodeCpcaMatrixTransfer(std::span<const std::uint8_t> bytes, int bands, CpcaMatrixTransfer* out) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "decodeCpcaMatrixTransfer: out is null");
  TransferBlobInfo info;
  if (Status s = readTransferBlobInfo(bytes, &info); !s.isOk()) return s;
  if (!info.matrix || info.encoding != TransferEncoding::kCpca) {
    return Status::error(StatusCode::kInvalidArgument, std::string("the transfer blob is ") + (info.matrix ? "matrix " : "vector ") +
                                                           transferEncodingName(info.encoding) + ", not matrix CPCA");
  }
  if (bands == 0) {
    if (info.bandsAvailable < 1) {
      return Status::error(StatusCode::kTruncated, "the matrix transfer blob holds no complete shell yet");
    }
    bands = info.bandsAvailable;
  }
  if (Status s = checkBandRequest(info, bands); !s.isOk()) return s;
  CpcaMatrixTransfer cpca;
  cpca.order = info.order;
  cpca.bands = bands;
  cpca.channels = info.channels;
  cpca.packing = info.packing;
  cpca.vertexCount = info.vertexCount;
  cpca.clusterCount = info.clusterCount;
  cpca.weightBits = info.weightBits;
  cpca.vectors = info.vectors;
  cpca.basisBits = info.basisBits;
  if (Status s = decodeIds(bytes, info, &cpca); !s.isOk()) return s;
  std::vector<std::int32_t> largest;
  if (Status s = decodeWeights(bytes, info, &cpca, &largest); !s.isOk()) return s;
  const std::size_t K = info.clusterCount, N = static_cast<std::size_t>(info.vectors), C = static_cast<std::size_t>(info.channels);
  const std::size_t Eb = matrixEntryCount(bands, info.packing);
  // At most four times the shells' bytes: 4 bytes per stored float32, binary16 or int8.
  cpca.matrices.assign(K * (N + 1) * C * Eb, 0.0f);
  for (int b = 0; b < bands; ++b) {
    if (Status s = decodeShellPart(bytes, info, b, Eb, &cpca); !s.isOk()) return s;
  }
  // Every value a vertex of cluster k reconstructs, in any order of summation, is within
  // max|mean| + sum_j step |level_j| max|basis_j| (over the decoded block).
  for (std::size_t k = 0; k < K; ++k) {
    const float* m = &cpca.matrices[k * (N + 1) * C * Eb];
    double bound = 0.0;
    for (std::size_t i = 0; i < C * Eb; ++i) bound = std::max(bound, std::fabs(static_cast<double>(m[i])));
    for (std::size_t j = 0; j < N; ++j) {
      double basisMax = 0.0;
      const float* b = m + (j + 1) * C * Eb;
      for (std::size_t i = 0; i < C * Eb; ++i) basisMax = std::max(basisMax, std::fabs(static_cast<double>(b[i])));
      bound += static_cast<double>(cpca.steps[k]) * largest[k * N + j] * basisMax;
    }
    if (bound > kMaxTransferMagnitudeRounded) {
      return corrupt("matrix CPCA cluster " + std::to_string(k) + " can reconstruct values up to " + std::to_string(bound) +
                     ", beyond the transfer range (65504)");
    }
  }
  *out = std::move(cpca);
  return Status::ok();
}

Status cpcaMatrixReconstruct(const CpcaMatrixTransfer& cpca, std::span<float> out) {
  const std::size_t V = cpca.vertexCount, K = cpca.clusterCount, C = static_cast<std::size_t>(cpca.channels);
  const bool packingOk = cpca.packing == MatrixPacking::kSymmetric || cpca.packing == MatrixPacking::kFull;
  const bool shapeOk = packingOk && (C == 1 || C == 3) && cpca.bands >= 1 && cpca.bands <= kMaxMatrixOrder && cpca.vectors >= 0;
  const std::size_t Eb = shapeOk ? matrixEntryCount(cpca.bands, cpca.packing) : 0;
  const std::size_t N = shapeOk ? static_cast<std::size_t>(cpca.vectors) : 0;
  if (!shapeOk || out.size() != V * C * Eb) {
    return Status::error(StatusCode::kSizeMismatch, "output holds " + std::to_string(out.size()) + " floats, the order-" +
                                                        std::to_string(cpca.bands) + " matrix transfer needs " +
                                                        std::to_string(V * C * Eb));
  }
  bool consistent = cpca.clusterOf.size() == V && cpca.weights.size() == V * N && cpca.matrices.size() == K * (N + 1) * C * Eb;
  for (std::size_t v = 0; v < V && consistent; ++v) consistent = cpca.clusterOf[v] < K;
  if (!consistent) return Status::error(StatusCode::kSizeMismatch, "CPCA matrix transfer arrays disagree with its counts");
  const std::size_t D = C * Eb;
  for (std::size_t v = 0; v < V; ++v) {
    const float* m = &cpca.matrices[cpca.clusterOf[v] * (N + 1) * D];
    const float* w = cpca.weights.data() + v * N;  // N may be 0: no element to index
    float* o = &out[v * D];
    for (std::size_t i = 0; i < D; ++i) o[i] = m[i];
    for (std::size_t j = 0; j < N; ++j) {
      const float* b = m + (j + 1) * D;
      const float wj = w[j];
      for (std::size_t i = 0; i < D; ++i) o[i] += wj * b[i];
    }
    for (std::size_t i = 0; i < D; ++i) {
      if (!std::isfinite(o[i])) {
        return Status::error(StatusCode::kCorrupt, "CPCA matrix transfer of vertex " + std::to_string(v) + " reconstructs to a non-finite value");
      }
    }
  }
  return Status::ok();
}

}  // namespace prt
