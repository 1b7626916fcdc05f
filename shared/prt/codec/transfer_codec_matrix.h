// Matrix transfer in the codec (docs/transfer-codec.md "Matrices"), internal: input checks
// shared by the encoders, and the matrix CPCA encoder (transfer_codec_matrix_cpca.cpp).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "prt/status.h"
#include "prt/transfer_codec.h"
#include "transfer_codec_container.h"

namespace prt::transfer_codec {

// Relative RMS error and max |a - b| of `b` against `a` (energy = sum a^2).
double matrixRelativeError(std::span<const float> a, std::span<const float> b, double energy, double* maxAbs);

// Chooses cluster count K, basis count N' and the weight quantisation to meet
// settings.cpcaTargetError at the smallest estimated size, verified by decoding; writes the
// blob to *out. Input already checked (encodeTransferMatrix).
Status encodeMatrixCpca(std::span<const float> packed, int order, MatrixPacking packing, int channels,
                        const TransferCodecSettings& settings, std::vector<std::uint8_t>* out, TransferEncodeReport* report);

}  // namespace prt::transfer_codec
