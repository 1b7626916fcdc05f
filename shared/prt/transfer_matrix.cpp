#include "prt/transfer_matrix.h"

#include "prt/sh_basis.h"

namespace prt {

const char* matrixPackingName(MatrixPacking packing) {
  switch (packing) {
    case MatrixPacking::kSymmetric: return "symmetric";
    case MatrixPacking::kFull: return "full";
  }
  return "unknown";
}

void applyPackedMatrixUnchecked(const float* packed, MatrixPacking packing, std::size_t rows, const float* v,
                                float* out) noexcept {
  for (std::size_t i = 0; i < rows; ++i) out[i] = 0.0f;
  if (packing == MatrixPacking::kSymmetric) {
    // Row i of the lower triangle holds (i, 0..i); each off-diagonal entry feeds two rows.
    for (std::size_t i = 0; i < rows; ++i) {
      const float* row = packed + i * (i + 1) / 2;
      for (std::size_t j = 0; j < i; ++j) {
        out[i] += row[j] * v[j];
        out[j] += row[j] * v[i];
      }
      out[i] += row[i] * v[i];
    }
    return;
  }
  for (std::size_t k = 0; k < rows; ++k) {
    const float* shell = packed + k * k;
    for (std::size_t j = 0; j < k; ++j) out[k] += shell[j] * v[j];       // row k, columns < k
    for (std::size_t i = 0; i < k; ++i) out[i] += shell[k + i] * v[k];   // column k, rows < k
    out[k] += shell[2 * k] * v[k];
  }
}

Status applyPackedMatrix(std::span<const float> packed, int order, MatrixPacking packing, std::span<const float> v,
                         std::span<float> out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (packing != MatrixPacking::kSymmetric && packing != MatrixPacking::kFull) {
    return Status::error(StatusCode::kInvalidArgument, "unknown matrix packing");
  }
  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(order));
  if (packed.size() != matrixEntryCount(order, packing) || v.size() != n2 || out.size() != n2) {
    return Status::error(StatusCode::kSizeMismatch, "packed matrix, vector and output sizes disagree with the order");
  }
  applyPackedMatrixUnchecked(packed.data(), packing, n2, v.data(), out.data());
  return Status::ok();
}

}  // namespace prt
