// encodeTransferMatrix / decodeTransferMatrix (prt/transfer_codec.h, docs/transfer-codec.md
// "Matrices"): the per-entry encodings (f32, f16, q16, q8), one part per shell, stored like
// a vector band with channels * shellEntries streams; CPCA goes to encodeMatrixCpca.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "prt/transfer_codec.h"
#include "transfer_codec_container.h"
#include "transfer_codec_decode_util.h"
#include "prt/half_float.h"
#include "transfer_codec_matrix.h"
#include "transfer_codec_streams.h"

namespace prt {
namespace {

using namespace transfer_codec;  // NOLINT: the codec's own internals

Status invalid(std::string message) { return Status::error(StatusCode::kInvalidArgument, std::move(message)); }

// As the vector encoder's: a key ordered like the float, a bijection on bit patterns.
std::int32_t orderedKey(std::uint32_t bits, int width) {
  const std::uint32_t signBit = 1u << (8 * width - 1);
  const std::int64_t magnitude = bits & (signBit - 1u);
  return static_cast<std::int32_t>((bits & signBit) ? -1 - magnitude : magnitude);
}

std::uint32_t bitsFromKey(std::int32_t key, int width) {
  if (key >= 0) return static_cast<std::uint32_t>(key);
  const std::uint32_t signBit = 1u << (8 * width - 1);
  return signBit | static_cast<std::uint32_t>(-1 - static_cast<std::int64_t>(key));
}

float quantStep(double maxAbs, int levels) {
  if (maxAbs == 0.0) return 0.0f;
  float step = std::max(static_cast<float>(maxAbs / levels), std::numeric_limits<float>::min());
  while (static_cast<double>(step) * levels < maxAbs) step = std::nextafter(step, 2.0f * step + 1.0f);
  return step;
}

// Row weights (TransferCodecSettings::cpcaMatrixRowWeights): none, or order^2 weights in
// (0, 1] for CPCA. The per-entry encodings bound each entry's error, so a weight has nothing
// to change there; the upper bound keeps scaled entries within the transfer range.
Status checkRowWeights(const TransferCodecSettings& s, int order) {
  const std::vector<double>& w = s.cpcaMatrixRowWeights;
  if (w.empty()) return Status::ok();
  if (s.encoding != TransferEncoding::kCpca) return invalid("row weights apply to matrix CPCA only");
  const std::size_t rows = static_cast<std::size_t>(order) * static_cast<std::size_t>(order);
  if (w.size() != rows) {
    return invalid("row weights: " + std::to_string(w.size()) + " given for " + std::to_string(rows) + " rows (order^2)");
  }
  for (std::size_t i = 0; i < rows; ++i) {
    if (!(w[i] > 0.0 && w[i] <= 1.0)) return invalid("row weight " + std::to_string(i) + " is " + std::to_string(w[i]) + ", outside (0, 1]");
  }
  return Status::ok();
}

Status checkMatrixInput(std::span<const float> packed, int order, MatrixPacking packing, int channels,
                        const TransferCodecSettings& s) {
  if (order < 1 || order > kMaxMatrixOrder) {
    return invalid("matrix order " + std::to_string(order) + " is outside 1.." + std::to_string(kMaxMatrixOrder));
  }
  if (packing != MatrixPacking::kSymmetric && packing != MatrixPacking::kFull) {
    return invalid("unknown matrix packing " + std::to_string(static_cast<int>(packing)));
  }
  if (channels != 1 && channels != 3) return invalid("channels is " + std::to_string(channels) + " (expected 1 or 3)");
  const std::size_t stride = static_cast<std::size_t>(channels) * matrixEntryCount(order, packing);
  if (packed.empty() || packed.size() % stride != 0) {
    return Status::error(StatusCode::kSizeMismatch, "matrix transfer has " + std::to_string(packed.size()) +
                                                        " floats, not a positive multiple of channels * packed entries = " +
                                                        std::to_string(stride));
  }
  if (packed.size() / stride > kMaxTransferVertices) {
    return invalid("matrix transfer has " + std::to_string(packed.size() / stride) + " vertices, more than " +
                   std::to_string(kMaxTransferVertices));
  }
  switch (s.encoding) {
    case TransferEncoding::kFloat32:
    case TransferEncoding::kFloat16:
    case TransferEncoding::kQuant16:
    case TransferEncoding::kQuant8: break;
    case TransferEncoding::kCpca:
      if (s.cpcaWeightBits != 8 && s.cpcaWeightBits != 16) {
        return invalid("CPCA weight bits is " + std::to_string(s.cpcaWeightBits) + " (expected 8 or 16)");
      }
      if (!(s.cpcaTargetError > 0.0 && s.cpcaTargetError < 1.0)) {
        return invalid("CPCA target error " + std::to_string(s.cpcaTargetError) + " is outside (0, 1)");
      }
      if (s.cpcaMaxClusters < 1 || static_cast<std::uint32_t>(s.cpcaMaxClusters) > kMaxTransferClusters) {
        return invalid("CPCA cluster limit " + std::to_string(s.cpcaMaxClusters) + " is outside 1.." +
                       std::to_string(kMaxTransferClusters));
      }
      if (s.cpcaBasisBits != 8 && s.cpcaBasisBits != 16) {
        return invalid("CPCA basis bits is " + std::to_string(s.cpcaBasisBits) + " (expected 8 or 16)");
      }
      break;
    default: return invalid("unknown encoding " + std::to_string(static_cast<int>(s.encoding)));
  }
  if (Status st = checkRowWeights(s, order); !st.isOk()) return st;
  for (std::size_t i = 0; i < packed.size(); ++i) {
    const float x = packed[i];
    if (std::fabs(x) <= kMaxTransferMagnitude) continue;  // the common case; NaN falls through
    const std::string at = "vertex " + std::to_string(i / stride) + ", value " + std::to_string(i % stride);
    if (!std::isfinite(x)) return Status::error(StatusCode::kNotFinite, "matrix transfer value at " + at + " is not finite");
    return invalid("matrix transfer value " + std::to_string(x) + " at " + at +
                   " is beyond the largest an asset may hold (65504, kMaxTransferMagnitude)");
  }
  return Status::ok();
}

// Shell `band` of every vertex: streams (channel, shell entry), as a vector band's.
PartPayload shellPart(std::span<const float> packed, int order, MatrixPacking packing, int channels, int band,
                      TransferEncoding encoding) {
  const std::size_t E = matrixEntryCount(order, packing), first = matrixEntryCount(band, packing);
  const std::size_t S = static_cast<std::size_t>(shellEntries(band, packing)), C = static_cast<std::size_t>(channels);
  const std::size_t vertices = packed.size() / (E * C), streams = C * S;
  const bool quantised = encoding == TransferEncoding::kQuant16 || encoding == TransferEncoding::kQuant8;
  const int bytesPerValue = valueBytes(encoding);
  const int levels = quantised ? quantLevels(8 * bytesPerValue) : 0;
  PartPayload p;
  p.band = band;
  std::vector<std::int32_t> values(streams * vertices);
  for (std::size_t s = 0; s < streams; ++s) {
    const std::size_t c = s / S, e = s % S;
    auto x = [&](std::size_t v) { return packed[(v * C + c) * E + first + e]; };
    std::int32_t* out = &values[s * vertices];
    if (quantised) {
      double maxAbs = 0.0;
      for (std::size_t v = 0; v < vertices; ++v) maxAbs = std::max(maxAbs, std::fabs(static_cast<double>(x(v))));
      const float step = quantStep(maxAbs, levels);
      putF32(p.bytes, step);
      for (std::size_t v = 0; v < vertices; ++v) {
        const double q = step > 0.0f ? std::nearbyint(static_cast<double>(x(v)) / step) : 0.0;
        out[v] = static_cast<std::int32_t>(std::clamp(q, -static_cast<double>(levels), static_cast<double>(levels)));
      }
    } else if (encoding == TransferEncoding::kFloat16) {
      for (std::size_t v = 0; v < vertices; ++v) out[v] = orderedKey(floatToHalf(x(v)), 2);
    } else {
      for (std::size_t v = 0; v < vertices; ++v) out[v] = orderedKey(floatBits(x(v)), 4);
    }
  }
  putStreamGroup(values, streams, vertices, bytesPerValue, p.bytes);
  return p;
}

Status decodeShell(std::span<const std::uint8_t> bytes, const TransferBlobInfo& info, std::size_t index, int bands,
                   std::span<float> out) {
  const TransferPartInfo& part = info.parts[index];
  if (Status s = checkPartCrc(bytes, index, part); !s.isOk()) return s;
  const int l = part.band;
  const std::size_t C = static_cast<std::size_t>(info.channels), S = static_cast<std::size_t>(shellEntries(l, info.packing));
  const std::size_t Eb = matrixEntryCount(bands, info.packing), first = matrixEntryCount(l, info.packing);
  const std::size_t streams = C * S, vertices = info.vertexCount;
  const bool quantised = info.encoding == TransferEncoding::kQuant16 || info.encoding == TransferEncoding::kQuant8;
  const int bytesPerValue = valueBytes(info.encoding);
  const int levels = quantised ? quantLevels(8 * bytesPerValue) : 0;
  const std::uint8_t* p = bytes.data() + part.offset;
  const std::uint8_t* group = p + (quantised ? 4 * streams : 0);
  std::vector<std::int32_t> values(vertices);
  for (std::size_t s = 0; s < streams; ++s) {
    const std::size_t c = s / S, e = s % S;
    const std::string what = partName(index, part) + ", channel " + std::to_string(c) + " entry " + std::to_string(first + e);
    float step = 0.0f;
    if (quantised) {
      step = readLeF32(p + 4 * s);
      if (Status st = checkStep(step, levels, what + ": step"); !st.isOk()) return st;
    }
    if (!getStream(group, streams, vertices, bytesPerValue, s, values)) {
      return Status::error(StatusCode::kCorrupt, what + ": unknown filter " + std::to_string(group[s]));
    }
    for (std::size_t v = 0; v < vertices; ++v) {
      float x = 0.0f;
      if (quantised) {
        if (values[v] < -levels || values[v] > levels) {
          return Status::error(StatusCode::kCorrupt, what + ", vertex " + std::to_string(v) + ": level " +
                                                         std::to_string(values[v]) + " is outside +-" + std::to_string(levels));
        }
        x = static_cast<float>(values[v]) * step;
      } else if (info.encoding == TransferEncoding::kFloat16) {
        const auto h = static_cast<std::uint16_t>(bitsFromKey(values[v], 2));
        if (!isFiniteHalf(h)) {
          return Status::error(StatusCode::kCorrupt, what + ", vertex " + std::to_string(v) + ": not a finite float16");
        }
        x = halfToFloat(h);
      } else {
        x = floatFromBits(bitsFromKey(values[v], 4));
        if (!(std::fabs(x) <= kMaxTransferMagnitude)) {  // NaN fails too
          return Status::error(StatusCode::kCorrupt, what + ", vertex " + std::to_string(v) + ": " + std::to_string(x) +
                                                         " is not finite or beyond the transfer range (65504)");
        }
      }
      out[(v * C + c) * Eb + first + e] = x;
    }
  }
  return Status::ok();
}

// Header, band request and output size of a matrix decode.
Status matrixRequest(std::span<const std::uint8_t> bytes, int bands, TransferBlobInfo* info) {
  if (Status s = readTransferBlobInfo(bytes, info); !s.isOk()) return s;
  if (!info->matrix) {
    return invalid("the transfer blob holds vectors: decode it with decodeTransfer");
  }
  return checkBandRequest(*info, bands);
}

}  // namespace

namespace transfer_codec {

double matrixRelativeError(std::span<const float> a, std::span<const float> b, double energy, double* maxAbs) {
  double sum = 0.0;
  *maxAbs = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double e = static_cast<double>(a[i]) - static_cast<double>(b[i]);
    sum += e * e;
    *maxAbs = std::max(*maxAbs, std::fabs(e));
  }
  return energy > 0.0 ? std::sqrt(sum / energy) : (sum > 0.0 ? INFINITY : 0.0);
}

}  // namespace transfer_codec

Status encodeTransferMatrix(std::span<const float> packed, int order, MatrixPacking packing, int channels,
                            const TransferCodecSettings& settings, std::vector<std::uint8_t>* out,
                            TransferEncodeReport* report) {
  if (out == nullptr) return invalid("encodeTransferMatrix: out is null");
  if (Status s = checkMatrixInput(packed, order, packing, channels, settings); !s.isOk()) return s;
  if (settings.encoding == TransferEncoding::kCpca) {
    TransferEncodeReport r;
    if (Status s = encodeMatrixCpca(packed, order, packing, channels, settings, out, &r); !s.isOk()) return s;
    if (report) *report = std::move(r);
    return Status::ok();
  }
  BlobHeader header;
  header.encoding = settings.encoding;
  header.matrix = true;
  header.packing = packing;
  header.order = order;
  header.channels = channels;
  header.vertexCount = static_cast<std::uint32_t>(packed.size() / (static_cast<std::size_t>(channels) * matrixEntryCount(order, packing)));
  std::vector<PartPayload> parts;
  for (int l = 0; l < order; ++l) parts.push_back(shellPart(packed, order, packing, channels, l, settings.encoding));
  std::vector<std::uint8_t> blob;
  assembleBlob(header, parts, &blob);
  // Always decoded once: the encoder never writes what the reader would reject.
  std::vector<float> decoded(packed.size());
  if (Status s = decodeTransferMatrix(blob, order, decoded); !s.isOk()) {
    return invalid("the encoded matrix transfer does not decode: " + s.toString());
  }
  if (report) {
    double energy = 0.0;
    for (float x : packed) energy += static_cast<double>(x) * x;
    *report = TransferEncodeReport{};
    report->bytes = blob.size();
    report->relativeError = matrixRelativeError(packed, decoded, energy, &report->maxAbsError);
  }
  *out = std::move(blob);
  return Status::ok();
}

Status decodeTransferMatrix(std::span<const std::uint8_t> bytes, int bands, std::span<float> out) {
  TransferBlobInfo info;
  if (Status s = matrixRequest(bytes, bands, &info); !s.isOk()) return s;
  const std::uint64_t want = std::uint64_t{info.vertexCount} * static_cast<std::uint64_t>(info.channels) *
                             matrixEntryCount(bands, info.packing);
  if (out.size() != want) {
    return Status::error(StatusCode::kSizeMismatch, "output holds " + std::to_string(out.size()) + " floats, the " +
                                                        std::to_string(bands) + "-band matrix transfer needs " + std::to_string(want));
  }
  if (info.encoding == TransferEncoding::kCpca) {
    CpcaMatrixTransfer cpca;
    if (Status s = decodeCpcaMatrixTransfer(bytes, bands, &cpca); !s.isOk()) return s;
    return cpcaMatrixReconstruct(cpca, out);
  }
  for (int l = 0; l < bands; ++l) {
    if (Status s = decodeShell(bytes, info, static_cast<std::size_t>(l), bands, out); !s.isOk()) return s;
  }
  return Status::ok();
}

Status decodeTransferMatrix(std::span<const std::uint8_t> bytes, int bands, std::vector<float>* out) {
  if (out == nullptr) return invalid("decodeTransferMatrix: out is null");
  TransferBlobInfo info;
  if (Status s = matrixRequest(bytes, bands, &info); !s.isOk()) return s;
  const std::uint64_t floats = std::uint64_t{info.vertexCount} * static_cast<std::uint64_t>(info.channels) *
                               matrixEntryCount(bands, info.packing);
  if (floats > std::numeric_limits<std::size_t>::max() / sizeof(float)) {  // wasm: 32-bit size_t
    return invalid("the decoded matrix transfer (" + std::to_string(floats) + " floats) is too large for this platform");
  }
  std::vector<float> decoded(static_cast<std::size_t>(floats));
  if (Status s = decodeTransferMatrix(bytes, bands, std::span<float>(decoded)); !s.isOk()) return s;
  *out = std::move(decoded);
  return Status::ok();
}

}  // namespace prt
