// Checks shared by the transfer codec's decoders (internal).
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include "prt/status.h"
#include "prt/transfer_codec.h"

namespace prt::transfer_codec {

// "part 2 (band 1)", "part 0 (clusters)".
std::string partName(std::size_t index, const TransferPartInfo& part);

// kInvalidArgument unless 1 <= bands <= order; kTruncated when the bytes given hold fewer bands.
Status checkBandRequest(const TransferBlobInfo& info, int bands);

// kChecksumMismatch unless the part's bytes have its CRC-32C (bounds already validated).
Status checkPartCrc(std::span<const std::uint8_t> bytes, std::size_t index, const TransferPartInfo& part);

// kMaxTransferMagnitude with room for the rounding of a step (max|x| / levels, as a float)
// and of the sums a reconstruction makes.
inline constexpr double kMaxTransferMagnitudeRounded = kMaxTransferMagnitude * (1.0 + 1e-5);

// kCorrupt unless `step` is finite, >= 0 and step * levels stays within the transfer range
// (kMaxTransferMagnitudeRounded); `what` names it.
Status checkStep(float step, int levels, const std::string& what);

}  // namespace prt::transfer_codec
