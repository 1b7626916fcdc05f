// decodeTransfer (prt/transfer_codec.h) and the per-coefficient encodings' band decoder.
// The container checks are readTransferBlobInfo's; here each used part's checksum is
// verified before its bytes are interpreted, and every decoded value is range-checked.
#include <cmath>
#include <limits>
#include <string>

#include "prt/transfer_codec.h"
#include "transfer_codec_container.h"
#include "transfer_codec_decode_util.h"
#include "prt/half_float.h"
#include "transfer_codec_streams.h"

namespace prt {

namespace {

using namespace transfer_codec;  // NOLINT: the codec's own internals

// Float value of an ordered key of `width` bytes (the inverse of the encoder's orderedKey).
std::uint32_t bitsFromKey(std::int32_t key, int width) {
  if (key >= 0) return static_cast<std::uint32_t>(key);
  const std::uint32_t signBit = 1u << (8 * width - 1);
  return signBit | static_cast<std::uint32_t>(-1 - static_cast<std::int64_t>(key));
}

Status decodeBand(std::span<const std::uint8_t> bytes, const TransferBlobInfo& info, std::size_t index, int bands,
                  std::span<float> out) {
  const TransferPartInfo& part = info.parts[index];
  if (Status s = checkPartCrc(bytes, index, part); !s.isOk()) return s;
  const int l = part.band, width = 2 * l + 1, C = info.channels;
  const std::size_t streams = static_cast<std::size_t>(C * width), vertices = info.vertexCount;
  const std::size_t b2 = static_cast<std::size_t>(bands * bands), first = static_cast<std::size_t>(l * l);
  const bool quantised = info.encoding == TransferEncoding::kQuant16 || info.encoding == TransferEncoding::kQuant8;
  const int bytesPerValue = valueBytes(info.encoding);
  const int levels = quantised ? quantLevels(8 * bytesPerValue) : 0;
  const std::uint8_t* p = bytes.data() + part.offset;
  const std::uint8_t* group = p + (quantised ? 4 * streams : 0);
  std::vector<std::int32_t> values(vertices);
  for (std::size_t s = 0; s < streams; ++s) {
    const std::size_t c = s / static_cast<std::size_t>(width), m = s % static_cast<std::size_t>(width);
    const std::string what = partName(index, part) + ", channel " + std::to_string(c) + " coefficient " + std::to_string(first + m);
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
        if (!std::isfinite(x)) {
          return Status::error(StatusCode::kCorrupt, what + ", vertex " + std::to_string(v) + ": not a finite float32");
        }
        if (std::fabs(x) > kMaxTransferMagnitude) {
          return Status::error(StatusCode::kCorrupt, what + ", vertex " + std::to_string(v) + ": " + std::to_string(x) +
                                                         " is beyond the transfer range (65504)");
        }
      }
      out[(v * static_cast<std::size_t>(C) + c) * b2 + first + m] = x;
    }
  }
  return Status::ok();
}

}  // namespace

Status decodeTransfer(std::span<const std::uint8_t> bytes, int bands, std::span<float> out) {
  TransferBlobInfo info;
  if (Status s = readTransferBlobInfo(bytes, &info); !s.isOk()) return s;
  if (info.matrix) {
    return Status::error(StatusCode::kInvalidArgument, "the transfer blob holds matrices: decode it with decodeTransferMatrix");
  }
  if (Status s = checkBandRequest(info, bands); !s.isOk()) return s;
  const std::uint64_t want = std::uint64_t{info.vertexCount} * static_cast<std::uint64_t>(info.channels * bands * bands);
  if (out.size() != want) {
    return Status::error(StatusCode::kSizeMismatch, "output holds " + std::to_string(out.size()) + " floats, the " +
                                                        std::to_string(bands) + "-band transfer needs " + std::to_string(want));
  }
  if (info.encoding == TransferEncoding::kCpca) {
    CpcaTransfer cpca;
    if (Status s = decodeCpcaTransfer(bytes, bands, &cpca); !s.isOk()) return s;
    return cpcaReconstruct(cpca, out);
  }
  for (int l = 0; l < bands; ++l) {
    if (Status s = decodeBand(bytes, info, static_cast<std::size_t>(l), bands, out); !s.isOk()) return s;
  }
  return Status::ok();
}

Status decodeTransfer(std::span<const std::uint8_t> bytes, int bands, std::vector<float>* out) {
  TransferBlobInfo info;
  if (Status s = readTransferBlobInfo(bytes, &info); !s.isOk()) return s;
  if (info.matrix) {
    return Status::error(StatusCode::kInvalidArgument, "the transfer blob holds matrices: decode it with decodeTransferMatrix");
  }
  if (Status s = checkBandRequest(info, bands); !s.isOk()) return s;
  const std::uint64_t floats = std::uint64_t{info.vertexCount} * static_cast<std::uint64_t>(info.channels * bands * bands);
  if (floats > std::numeric_limits<std::size_t>::max() / sizeof(float)) {  // wasm: 32-bit size_t
    return Status::error(StatusCode::kInvalidArgument,
                         "the decoded transfer (" + std::to_string(floats) + " floats) is too large for this platform");
  }
  std::vector<float> decoded(static_cast<std::size_t>(floats));
  if (Status s = decodeTransfer(bytes, bands, std::span<float>(decoded)); !s.isOk()) return s;
  *out = std::move(decoded);
  return Status::ok();
}

}  // namespace prt
