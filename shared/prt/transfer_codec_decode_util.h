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

// kCorrupt unless `step` is finite, >= 0 and step * levels is finite; `what` names it.
Status checkStep(float step, int levels, const std::string& what);

}  // namespace prt::transfer_codec
