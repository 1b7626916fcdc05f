// encodeTransfer (prt/transfer_codec.h): input checks, the per-coefficient encodings
// (float32, float16, 16- and 8-bit quantisation), and the report measured on the decoded blob.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "prt/sh_basis.h"
#include "prt/transfer_codec.h"
#include "transfer_codec_container.h"
#include "transfer_codec_cpca.h"
#include "prt/half_float.h"
#include "transfer_codec_streams.h"

namespace prt {
namespace {

using namespace transfer_codec;  // NOLINT: the codec's own internals

Status invalid(std::string message) { return Status::error(StatusCode::kInvalidArgument, std::move(message)); }

std::string where(std::size_t index, int channels, int n2) {
  const std::size_t stride = static_cast<std::size_t>(channels * n2);
  return "vertex " + std::to_string(index / stride) + ", channel " + std::to_string((index % stride) / static_cast<std::size_t>(n2)) +
         ", coefficient " + std::to_string(index % static_cast<std::size_t>(n2));
}

Status checkInput(std::span<const float> transfer, int order, int channels, const TransferCodecSettings& s) {
  if (Status st = checkShOrder(order); !st.isOk()) return st;
  if (channels != 1 && channels != 3) return invalid("channels is " + std::to_string(channels) + " (expected 1 or 3)");
  const int n2 = order * order;
  const std::size_t stride = static_cast<std::size_t>(channels * n2);
  if (transfer.empty() || transfer.size() % stride != 0) {
    return Status::error(StatusCode::kSizeMismatch, "transfer has " + std::to_string(transfer.size()) +
                                                        " floats, not a positive multiple of channels * order^2 = " + std::to_string(stride));
  }
  if (transfer.size() / stride > kMaxTransferVertices) {
    return invalid("transfer has " + std::to_string(transfer.size() / stride) + " vertices, more than " + std::to_string(kMaxTransferVertices));
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
        return invalid("CPCA cluster limit " + std::to_string(s.cpcaMaxClusters) + " is outside 1.." + std::to_string(kMaxTransferClusters));
      }
      // cpcaBasisBits is matrix CPCA's: vector CPCA's bands store binary16 basis vectors
      // whatever it says, so one setting ("cpca16b8@0.04") serves an asset's vector and
      // matrix passes alike.
      break;
    default: return invalid("unknown encoding " + std::to_string(static_cast<int>(s.encoding)));
  }
  // Row weights describe a matrix's rows; a vector transfer has none to weight.
  if (!s.cpcaMatrixRowWeights.empty()) return invalid("row weights apply to matrix CPCA only, not to vector transfer");
  for (std::size_t i = 0; i < transfer.size(); ++i) {
    const float x = transfer[i];
    if (!std::isfinite(x)) return Status::error(StatusCode::kNotFinite, "transfer value at " + where(i, channels, n2) + " is not finite");
    if (std::fabs(x) > kMaxTransferMagnitude) {
      return invalid("transfer value " + std::to_string(x) + " at " + where(i, channels, n2) +
                     " is beyond the largest an asset may hold (65504, kMaxTransferMagnitude)");
    }
  }
  return Status::ok();
}

// Key of a float's bits that orders like the value and is a bijection on bit patterns:
// non-negative values keep their bits, negative ones become -1 - magnitude bits.
std::int32_t orderedKey(std::uint32_t bits, int width) {
  const std::uint32_t signBit = 1u << (8 * width - 1);
  const std::int64_t magnitude = bits & (signBit - 1u);
  return static_cast<std::int32_t>((bits & signBit) ? -1 - magnitude : magnitude);
}

// Smallest float step with max|x| / step <= levels; 0 when every value is 0.
float quantStep(double maxAbs, int levels) {
  if (maxAbs == 0.0) return 0.0f;
  float step = std::max(static_cast<float>(maxAbs / levels), std::numeric_limits<float>::min());
  while (static_cast<double>(step) * levels < maxAbs) step = std::nextafter(step, 2.0f * step + 1.0f);
  return step;
}

// One band of a per-coefficient encoding: [steps], filters, planes (docs/transfer-codec.md).
PartPayload bandPart(std::span<const float> transfer, int order, int channels, int band, TransferEncoding encoding) {
  const std::size_t n2 = static_cast<std::size_t>(order * order), width = static_cast<std::size_t>(2 * band + 1);
  const std::size_t vertices = transfer.size() / (n2 * static_cast<std::size_t>(channels));
  const std::size_t streams = static_cast<std::size_t>(channels) * width, first = static_cast<std::size_t>(band * band);
  const bool quantised = encoding == TransferEncoding::kQuant16 || encoding == TransferEncoding::kQuant8;
  const int bytesPerValue = valueBytes(encoding);
  const int levels = quantised ? quantLevels(8 * bytesPerValue) : 0;
  PartPayload p;
  p.band = band;
  std::vector<std::int32_t> values(streams * vertices);
  for (std::size_t s = 0; s < streams; ++s) {
    const std::size_t c = s / width, m = s % width;
    auto x = [&](std::size_t v) { return transfer[(v * static_cast<std::size_t>(channels) + c) * n2 + first + m]; };
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

}  // namespace

Status encodeTransfer(std::span<const float> transfer, int order, int channels, const TransferCodecSettings& settings,
                      std::vector<std::uint8_t>* out, TransferEncodeReport* report) {
  if (Status s = checkInput(transfer, order, channels, settings); !s.isOk()) return s;
  if (settings.encoding == TransferEncoding::kCpca) {
    TransferEncodeReport r;
    if (Status s = encodeCpca(transfer, order, channels, settings, out, &r); !s.isOk()) return s;
    // The reader bounds what a cluster can reconstruct (kMaxTransferMagnitude); transfer
    // within the range can still exceed that bound through its principal vectors.
    CpcaTransfer check;
    if (Status s = decodeCpcaTransfer(*out, order, &check); !s.isOk()) {
      out->clear();
      return invalid("the transfer cannot be stored as CPCA within the transfer range: " + s.message());
    }
    if (report) *report = std::move(r);
    return Status::ok();
  }
  BlobHeader header;
  header.encoding = settings.encoding;
  header.order = order;
  header.channels = channels;
  header.vertexCount = static_cast<std::uint32_t>(transfer.size() / static_cast<std::size_t>(channels * order * order));
  std::vector<PartPayload> parts;
  for (int l = 0; l < order; ++l) parts.push_back(bandPart(transfer, order, channels, l, settings.encoding));
  std::vector<std::uint8_t> blob;
  assembleBlob(header, parts, &blob);
  // Always decoded once: the encoder never writes what the reader would reject.
  std::vector<float> decoded(transfer.size());
  if (Status s = decodeTransfer(blob, order, decoded); !s.isOk()) {
    return invalid("the encoded transfer does not decode: " + s.toString());
  }
  if (report) {
    double sum = 0.0, energy = 0.0, maxAbs = 0.0;
    for (std::size_t i = 0; i < transfer.size(); ++i) {
      const double e = static_cast<double>(decoded[i]) - transfer[i];
      sum += e * e;
      energy += static_cast<double>(transfer[i]) * transfer[i];
      maxAbs = std::max(maxAbs, std::fabs(e));
    }
    *report = TransferEncodeReport{};
    report->bytes = blob.size();
    report->relativeError = energy > 0.0 ? std::sqrt(sum / energy) : 0.0;
    report->maxAbsError = maxAbs;
  }
  *out = std::move(blob);
  return Status::ok();
}

}  // namespace prt
