#include "transfer_codec_decode_util.h"

#include <cmath>

#include "prt/checksum.h"

namespace prt {

namespace transfer_codec {

std::string partName(std::size_t index, const TransferPartInfo& p) {
  return "part " + std::to_string(index) +
         (p.type == TransferPartType::kClusters  ? std::string(" (clusters)")
          : p.type == TransferPartType::kWeights ? std::string(" (weights)")
                                                 : " (band " + std::to_string(p.band) + ")");
}

Status checkBandRequest(const TransferBlobInfo& info, int bands) {
  if (bands < 1 || bands > info.order) {
    return Status::error(StatusCode::kInvalidArgument,
                         "requested " + std::to_string(bands) + " bands of an order-" + std::to_string(info.order) + " transfer");
  }
  if (bands > info.bandsAvailable) {
    return Status::error(StatusCode::kTruncated, "the transfer blob is cut short: it holds " + std::to_string(info.bandsAvailable) +
                                                     " complete bands, " + std::to_string(bands) + " requested");
  }
  return Status::ok();
}

Status checkPartCrc(std::span<const std::uint8_t> bytes, std::size_t index, const TransferPartInfo& p) {
  const std::uint32_t crc = crc32c(bytes.subspan(static_cast<std::size_t>(p.offset), static_cast<std::size_t>(p.size)));
  if (crc != p.crc) return Status::error(StatusCode::kChecksumMismatch, partName(index, p) + " checksum mismatch");
  return Status::ok();
}

Status checkStep(float step, int levels, const std::string& what) {
  if (!std::isfinite(step) || step < 0.0f) {
    return Status::error(StatusCode::kCorrupt, what + " is " + std::to_string(step) + " (expected a finite step >= 0)");
  }
  if (static_cast<double>(step) * levels > kMaxTransferMagnitudeRounded) {
    return Status::error(StatusCode::kCorrupt, what + " is " + std::to_string(step) + ": its " + std::to_string(levels) +
                                                   " levels reach beyond the transfer range (65504)");
  }
  return Status::ok();
}

}  // namespace transfer_codec

}  // namespace prt
